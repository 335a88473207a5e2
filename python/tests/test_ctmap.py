"""Tests of ctmap's Python bindings (issue 16, must-show 1), run by the test command through CTest
(tests/CMakeLists.txt: PythonBindings). Needs PYTHONPATH with build/python and CTMAP_BIN, the
`ctmap` program of the same build."""
import copy
import json
import os
import struct
import subprocess
import threading
import time

import numpy as np
import pytest

import ctmap


def data(rel):
    src = os.path.dirname(os.path.abspath(__file__))
    for d in (os.environ.get("CTMAP_DATA"), os.path.join(src, "..", "..", "data"),
              os.path.join(src, "..", "..", "..", "shared", "data"), os.path.join(src, "..", "..", ".cache", "data")):
        if d and os.path.isfile(os.path.join(d, rel)):
            return os.path.join(d, rel)
    raise FileNotFoundError(rel)


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    return struct.unpack(">II", head[16:24])


MESH = data("meshes/nefertiti.off")
FEATURES_FILE = data("features/nefertiti_astronaut.json")
FEATURES = json.load(open(FEATURES_FILE))["features"]
SIZE = png_size(data("images/astronaut.png"))


def obj_uvs(path):
    return np.array([[float(x) for x in line.split()[1:3]] for line in open(path) if line.startswith("vt ")])


def test_the_shipped_example_gives_the_maps_uvs_bit_for_bit(tmp_path):
    V, F = ctmap.read_mesh(MESH)
    r = ctmap.map_texture(V, F, FEATURES, image_size=SIZE)
    assert r["certificate"]["valid"]
    assert r["certificate"]["flipped"] == 0
    subprocess.run([os.environ["CTMAP_BIN"], "map", MESH, FEATURES_FILE, "-o", str(tmp_path / "map.obj"), "-q"], check=True)
    uv = obj_uvs(tmp_path / "map.obj")
    assert uv.shape == r["UV"].shape
    assert np.array_equal(uv, r["UV"])  # bitwise: the OBJ's numbers round-trip exactly
    # The input's vertices come first, unchanged; every corner UV is its vertex's.
    assert np.array_equal(r["V"][: len(V)], V)
    assert np.array_equal(r["UV_corners"], r["UV"][r["F"]])
    assert set(np.unique(r["chart"])) == {0}
    # The certificate of the returned map, recomputed from the arrays alone.
    fv = r["feature_vertex"]
    c = ctmap.certify(r["V"], r["F"], r["UV"], fv, r["UV"][fv])
    assert c["valid"] and c["triangles"] == len(r["F"])


def test_a_flipped_triangle_fails_the_certificate():
    V, F = ctmap.read_mesh(MESH)
    r = ctmap.map_texture(V, F, FEATURES, image_size=SIZE)
    uv = r["UV"].copy()
    a, b, c = r["F"][100]
    uv[a] = uv[b] + (uv[b] - uv[a]) * 0 + 2 * (uv[c] - uv[b])  # far across its opposite edge
    assert not ctmap.certify(r["V"], r["F"], uv)["valid"]


def with_change(change):
    fs = copy.deepcopy(FEATURES)
    change(fs)
    return fs


def named(i):
    return FEATURES[i]["name"]


INTERIOR = [i for i, f in enumerate(FEATURES) if not f["name"].startswith("rim")]


@pytest.mark.parametrize("case, features, words", [
    ("duplicate name", with_change(lambda fs: fs[INTERIOR[1]].update(name=named(INTERIOR[0]))),
     ["two features are named", named(INTERIOR[0])]),
    ("vertex out of range", with_change(lambda fs: fs[INTERIOR[0]].update(vertex=99999)),
     [named(INTERIOR[0]), "99999", "does not exist"]),
    ("same vertex", with_change(lambda fs: fs[INTERIOR[1]].update(vertex=fs[INTERIOR[0]]["vertex"])),
     [named(INTERIOR[0]), named(INTERIOR[1]), "same mesh vertex"]),
    ("same image point", with_change(lambda fs: fs[INTERIOR[1]].update(image=list(fs[INTERIOR[0]]["image"]))),
     [named(INTERIOR[1])]),
    ("non-finite image point", with_change(lambda fs: fs[INTERIOR[0]].update(image=[float("nan"), 3.0])),
     [named(INTERIOR[0]), "finite"]),
    ("image point outside", with_change(lambda fs: fs[INTERIOR[0]].update(image=[-5.0, 3.0])),
     [named(INTERIOR[0]), "outside the image"]),
])
def test_bad_features_raise_value_error_naming_the_feature(case, features, words):
    V, F = ctmap.read_mesh(MESH)
    with pytest.raises(ValueError) as e:
        ctmap.map_texture(V, F, features, image_size=SIZE)
    for w in words:
        assert w in str(e.value), (case, str(e.value))


def test_wrong_python_types_raise_value_error():
    V, F = ctmap.read_mesh(MESH)
    with pytest.raises(ValueError, match="is not a dict"):
        ctmap.map_texture(V, F, [None] + FEATURES, image_size=SIZE)
    with pytest.raises(ValueError, match=named(INTERIOR[0])):
        ctmap.map_texture(V, F, with_change(lambda fs: fs[INTERIOR[0]].update(image="here")), image_size=SIZE)
    def far_point(fs):
        fs[INTERIOR[0]].pop("vertex", None)
        fs[INTERIOR[0]]["point"] = [0.0, 0.0, 50.0]

    with pytest.raises(ValueError, match="off the surface"):
        ctmap.map_texture(V, F, with_change(far_point), image_size=SIZE)


def test_bad_arrays_raise_value_error():
    V, F = ctmap.read_mesh(MESH)
    with pytest.raises(ValueError, match="out of range"):
        ctmap.map_texture(V, np.vstack([F, [[0, 1, len(V)]]]), FEATURES, image_size=SIZE)
    with pytest.raises(ValueError, match="n x 3"):
        ctmap.map_texture(V[:, :2], F, FEATURES, image_size=SIZE)
    bad = V.copy()
    bad[5, 1] = np.inf
    with pytest.raises(ValueError, match="vertex 5"):
        ctmap.map_texture(bad, F, FEATURES, image_size=SIZE)
    with pytest.raises(ValueError, match="not a clean topological disc"):  # a third face on edge 0-1 of face 0
        ctmap.map_texture(np.vstack([V, [[9.0, 9.0, 9.0]]]), np.vstack([F, [[F[0][0], F[0][1], len(V)]]]), FEATURES,
                          image_size=SIZE)
    with pytest.raises(ValueError, match="image_size"):
        ctmap.map_texture(V, F, FEATURES)


def test_the_gil_is_released_while_mapping():
    V, F = ctmap.read_mesh(data("meshes/lion-head.off"))
    features = json.load(open(data("features/lion-head_chelsea.json")))["features"]
    size = png_size(data("images/chelsea.png"))
    results, ticks = [], [0]

    def run():
        results.append(ctmap.map_texture(V, F, features, image_size=size))

    threads = [threading.Thread(target=run) for _ in range(2)]  # two maps at once
    start = time.monotonic()
    for t in threads:
        t.start()
    while any(t.is_alive() for t in threads):  # this thread runs Python while they map
        ticks[0] += 1
        time.sleep(0.001)
    elapsed = time.monotonic() - start
    for t in threads:
        t.join()
    assert len(results) == 2
    assert all(r["certificate"]["valid"] for r in results)
    assert np.array_equal(results[0]["UV"], results[1]["UV"])
    # With the GIL held by a map, this loop would stall for the whole map (seconds); released,
    # it ticks about once a millisecond.
    assert elapsed > 0.5 and ticks[0] > 0.2 * elapsed * 1000, (elapsed, ticks[0])
