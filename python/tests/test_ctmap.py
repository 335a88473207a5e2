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


def read_png_rgba(path):
    """A PNG (8-bit RGB or RGBA, non-interlaced) as an H x W x 4 uint8 array, with zlib alone."""
    import zlib
    data = open(path, "rb").read()
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (2, 6)
            channels = 4 if colour == 6 else 3
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = np.frombuffer(zlib.decompress(idat), np.uint8).reshape(height, 1 + width * channels)
    out = np.zeros((height, width * channels), np.int32)
    prev = np.zeros(width * channels, np.int32)
    for y in range(height):
        kind, line = raw[y, 0], raw[y, 1:].astype(np.int32)
        row = np.zeros_like(line)
        for x in range(len(line)):
            a = row[x - channels] if x >= channels else 0
            b, c = prev[x], (prev[x - channels] if x >= channels else 0)
            p = a + b - c
            pred = [0, a, b, (a + b) // 2,
                    a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else (b if abs(p - b) <= abs(p - c) else c)][kind]
            row[x] = (line[x] + pred) & 255
        out[y], prev = row, row
    img = out.reshape(height, width, channels).astype(np.uint8)
    if channels == 3:
        img = np.concatenate([img, np.full((height, width, 1), 255, np.uint8)], axis=2)
    return img


def test_bake_onto_the_mesh_itself_is_exact_and_matches_the_cli(tmp_path):
    # Issue 42: bake() on arrays gives the texture `ctmap bake` writes for the same map and layout.
    V, F = ctmap.read_mesh(MESH)
    r = ctmap.map_texture(V, F, FEATURES, image_size=SIZE)
    assert len(r["input_face"]) == len(r["F"])
    lo, hi = V.min(axis=0), V.max(axis=0)
    UV = 0.05 + 0.9 * (V[:, :2] - lo[:2]) / (hi[:2] - lo[:2])
    photo = read_png_rgba(data("images/astronaut.png"))
    b = ctmap.bake(r, photo, V, F, UV, size=(256, 256))
    assert b["exact"] and b["texture"].shape == (256, 256, 4) and b["covered"].sum() == b["covered_texels"] > 10000
    assert (b["texture"][b["covered"]][:, 3] == 255).all()
    ctmap.write_obj(str(tmp_path / "map.obj"), r["V"], r["F"], r["UV"], data("images/astronaut.png"))
    ctmap.write_obj(str(tmp_path / "onto.obj"), V, F, UV)
    subprocess.run([os.environ["CTMAP_BIN"], "bake", str(tmp_path / "map.obj"), str(tmp_path / "onto.obj"), "-o",
                    str(tmp_path / "baked.png"), "--size", "256", "-q"], check=True)
    cli = read_png_rgba(tmp_path / "baked.png")
    # The OBJ from write_obj has no input_face record: the CLI finds it again (same faces, same texture).
    assert np.array_equal(cli, b["texture"])
    with pytest.raises(ValueError, match="photo"):
        ctmap.bake(r, np.zeros((4, 4), np.uint8), V, F, UV)
    with pytest.raises(ValueError, match="UV"):
        ctmap.bake(r, photo, V, F, UV[:10])


def test_map_charts_on_a_closed_mesh_holds_every_feature_in_its_chart(tmp_path):
    # A closed mesh (cow) in the two charts `ctmap starter-features --charts 2` writes.
    cow = data("meshes/cow.off")
    out = tmp_path / "charts.json"
    subprocess.run([os.environ["CTMAP_BIN"], "starter-features", cow, "--image", data("images/astronaut.png"),
                    "--charts", "2", "-o", str(out)], check=True, capture_output=True)
    doc = json.load(open(out))
    V, F = ctmap.read_mesh(cow)
    r = ctmap.map_charts(V, F, doc["charts"])
    assert r["certificate"]["valid"] and r["chart_names"][:2] == ["front", "back"]
    assert len(r["input_face"]) == len(r["F"]) == len(r["chart"])
    by_chart = {c["name"]: c for c in doc["charts"]}
    for o in r["occurrences"]:
        ch = by_chart[r["chart_names"][o["chart"]]]
        f = next(f for f in ch["features"] if f["name"] == o["name"])
        w, h = ch["image_size"]
        assert o["uv"] == [f["image"][0] / w, 1 - f["image"][1] / h]  # exactly (image_to_uv's rule)
        corners = r["UV_corners"][(r["F"] == o["vertex"]).any(axis=1) & (r["chart"] == o["chart"])]
        faces = r["F"][(r["F"] == o["vertex"]).any(axis=1) & (r["chart"] == o["chart"])]
        assert all((corners[i][faces[i] == o["vertex"]] == o["uv"]).all() for i in range(len(faces)))
