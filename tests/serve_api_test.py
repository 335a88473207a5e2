"""Issue 15, must-show 2: `ctmap serve`'s JSON API under a sequence of random moves on lion-head /
chelsea, some of which make the layout invalid. Every answer must be a map that this script checks
on its own (every feature's UV where its pixel says, no UV triangle with area <= 0 in floating
point, the certificate valid) or a named error that leaves the session unchanged; maps are
compared with a full `ctmap map` of the same features (symmetric Dirichlet at most 5% above it); the server
must be alive at the end, have written nothing until asked to save, and load what it saved.

Usage: serve_api_test.py CTMAP_BIN SOURCE_DIR WORK_DIR
CTMAP_SERVE_MOVES (default 30; the issue's run: 200), CTMAP_SERVE_SEED (default 1)."""
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request

import numpy as np

ctmap, source, work = sys.argv[1:4]
for data in (os.environ.get("CTMAP_DATA"), os.path.join(source, "data"), os.path.join(source, "..", "shared", "data"),
             os.path.join(source, ".cache", "data")):
    if data and os.path.isfile(os.path.join(data, "meshes", "lion-head.off")):
        break
else:
    sys.exit("no lion-head.off (scripts/fetch_data.sh)")
features_file = os.path.join(source, "data", "features", "lion-head_chelsea.json")
moves = int(os.environ.get("CTMAP_SERVE_MOVES", "30"))
rng = random.Random(int(os.environ.get("CTMAP_SERVE_SEED", "1")))
mesh = os.path.join(data, "meshes", "lion-head.off")
image = os.path.join(data, "images", "chelsea.png")
shutil.rmtree(work, ignore_errors=True)
os.makedirs(os.path.join(work, "session"))
saved = os.path.join(work, "session", "features.json")
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what, flush=True)


def start(features_arg):
    p = subprocess.Popen([ctmap, "serve", mesh, image, features_arg, "--port", "0"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    line = p.stdout.readline()
    if "listening on http://127.0.0.1:" not in line:
        sys.exit(f"the server did not start: {line!r} {p.stderr.read()!r}")
    return p, line.split("http://")[1].split("/")[0]


def call(addr, method, path, body=None, headers=None):
    if headers is None:
        headers = {} if method == "GET" else {"Content-Type": "application/json"}
    data = None if method == "GET" else (body or "{}").encode()
    req = urllib.request.Request(f"http://{addr}{path}", data=data, method=method, headers=headers)
    try:
        with urllib.request.urlopen(req, timeout=600) as r:
            return r.status, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.read()


def verify_map(m, feats, width, height, label):
    """Checks a map answer against the features it was asked for, independently of the certificate."""
    uv = np.array(m["uv"]).reshape(-1, 2)
    faces = np.array(m["faces"]).reshape(-1, 3)
    check(m["certificate"]["valid"] and m["certificate"]["flipped"] == 0, f"{label}: certificate not valid")
    for f in feats:
        want = np.array([f["image"][0] / width, 1 - f["image"][1] / height])
        err = np.abs(uv[f["vertex"]] - want).max()
        check(err <= 1e-12, f"{label}: feature {f['name']} is {err:.3g} off its UV")
    a, b, c = uv[faces[:, 0]], uv[faces[:, 1]], uv[faces[:, 2]]
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    check((area > 0).all(), f"{label}: {(area <= 0).sum()} UV triangles with area <= 0")


def full_map_sd(feats, width, height, k):
    """The symmetric Dirichlet of `ctmap map` on the same features, through files."""
    path = os.path.join(work, f"full_{k}.json")
    json.dump({"image_size": [width, height], "units": "pixels", "features": feats}, open(path, "w"))
    report = os.path.join(work, f"full_{k}_report.json")
    subprocess.run([ctmap, "map", mesh, path, "--image", image, "-o", os.path.join(work, f"full_{k}.obj"),
                    "--report", report, "-q"], check=True)
    return json.load(open(report))["certificate"]["symmetric_dirichlet"]


server, addr = start(saved)
try:
    status, body = call(addr, "GET", "/api/state")
    state = json.loads(body)
    W, H = state["image"]["width"], state["image"]["height"]
    check(status == 200 and state["map"] is None and state["features"]["features"] == [], "a new session is empty")
    status, body = call(addr, "PUT", "/api/features", open(features_file).read())
    check(status == 200, f"PUT /api/features: {status} {body[:200]!r}")
    feats = json.loads(call(addr, "GET", "/api/state")[1])["features"]["features"]
    verify_map(json.loads(body), feats, W, H, "initial")
    names = [f["name"] for f in feats]
    mapped = refused = 0
    updates = {"full": 0, "incremental": 0}
    times = {"full": [], "incremental": []}
    because = {}
    t0 = time.time()
    for k in range(moves):
        name = rng.choice(names)
        old = next(f for f in feats if f["name"] == name)["image"]
        if rng.random() < 0.15:  # a far jump: often invalid (crossing, outside the border, outside the image)
            new = [rng.uniform(-40, W + 40), rng.uniform(-40, H + 40)]
        else:
            new = [min(max(old[0] + rng.gauss(0, 25), 0), W), min(max(old[1] + rng.gauss(0, 25), 0), H)]
        before_state = json.loads(call(addr, "GET", "/api/state")[1])
        status, body = call(addr, "POST", "/api/move", json.dumps({"name": name, "image": new}))
        answer = json.loads(body)
        after_state = json.loads(call(addr, "GET", "/api/state")[1])
        after = after_state["features"]["features"]
        if status == 200:
            mapped += 1
            updates[answer["update"]] += 1
            times[answer["update"]].append(answer["timings_ms"]["total"])
            if answer.get("full_because"):
                because[answer["full_because"]] = because.get(answer["full_because"], 0) + 1
            feats = after
            check(next(f for f in feats if f["name"] == name)["image"] == new, f"move {k}: the feature did not move")
            if "faces" not in answer:  # an answer from the last map: the cut mesh is the previous one
                check(answer["update"] == "incremental", f"move {k}: a full answer without its mesh")
                check(after_state["map"]["faces"] == before_state["map"]["faces"] and
                      after_state["map"]["vertices"] == before_state["map"]["vertices"],
                      f"move {k}: an answer without its mesh, but the cut mesh changed")
                check(after_state["map"]["uv"] == answer["uv"], f"move {k}: the state's UVs are not the answer's")
                check(answer["mesh_revision"] == before_state["map"]["mesh_revision"],
                      f"move {k}: an answer without its mesh names another mesh revision")
                answer = dict(answer, faces=after_state["map"]["faces"])
            else:
                check(answer["mesh_revision"] == (before_state["map"] or {}).get("mesh_revision", 0) + 1,
                      f"move {k}: a full answer does not name a new mesh revision")
            verify_map(answer, feats, W, H, f"move {k}")
            if mapped % 10 == 1 or k == moves - 1:
                full = full_map_sd(feats, W, H, k)
                sd = answer["certificate"]["symmetric_dirichlet"]
                # At most 5% above a full map (a full map can stop higher, at the optimiser's border
                # contacts: issue 11; a continued map staying lower is no fault).
                check(sd <= 1.05 * full, f"move {k}: symmetric Dirichlet {sd} vs {full} of ctmap map")
                print(f"move {k} ({answer['update']}): symmetric Dirichlet {sd:.4f}, ctmap map {full:.4f}", flush=True)
        else:
            refused += 1
            check(status == 422 and answer.get("exit_code") == 2, f"move {k}: status {status} {answer}")
            msg = answer.get("error", "")
            check(saved in msg or any(n in msg for n in names), f"move {k}: the error names neither the file nor a feature: {msg}")
            check(after_state == before_state, f"move {k}: a refused move changed the session (features, map or report)")
            print(f"move {k}: refused: {msg[:150]}", flush=True)
    print(f"{moves} moves: {mapped} mapped (each checked), {refused} refused with a named error, "
          f"{time.time() - t0:.0f} s", flush=True)
    for kind in ("incremental", "full"):
        if times[kind]:
            print(f"  {updates[kind]} {kind}: median {np.median(times[kind]):.0f} ms, "
                  f"95th percentile {np.percentile(times[kind], 95):.0f} ms (server time per move)", flush=True)
    for reason, n in because.items():
        print(f"  mapped in full because {reason}: {n}", flush=True)
    check(mapped > 0 and refused > 0, "the sequence should hold both valid and invalid layouts")
    # Only this server's own pages may use it: another Host (DNS rebinding) and a change sent as
    # text/plain (what a page elsewhere can send without asking) are refused, and change nothing.
    status, _ = call(addr, "GET", "/api/state", headers={"Host": "evil.example:80"})
    check(status == 403, f"a request for another Host answered {status}")
    status, _ = call(addr, "POST", "/api/save", headers={"Content-Type": "text/plain"})
    check(status == 415 and not os.path.exists(saved), f"a text/plain save answered {status}")
    status, body = call(addr, "POST", "/api/move", "not json")
    check(status == 400 and b"not JSON" in body, f"a move that is not JSON answered {status} {body[:100]!r}")
    status, body = call(addr, "POST", "/api/move", json.dumps({"name": "nose", "image": [1, "x"]}))
    check(status == 400, f"a move with a string coordinate answered {status}")
    status, body = call(addr, "POST", "/api/move", json.dumps({"name": "no such feature", "image": [10, 10]}))
    check(status == 422 and b"no such feature" in body, f"a move of an unknown feature answered {status}")
    check(not os.path.exists(saved), "the server wrote the features file before /api/save")
    check(os.listdir(os.path.join(work, "session")) == [], "the server wrote into its folder unasked")
    for path in ("/api/map.obj", "/api/map.glb"):
        status, body = call(addr, "GET", path)
        check(status == 200 and len(body) > 100, f"GET {path}: {status}")
    status, body = call(addr, "GET", "/api/map.mtl")
    check(status == 200 and b"map_Kd chelsea.png" in body, f"GET /api/map.mtl: {status} {body!r}")
    status, body = call(addr, "POST", "/api/save")
    check(status == 200 and os.path.exists(saved), f"POST /api/save: {status} {body!r}")
    check(sorted(os.listdir(os.path.join(work, "session"))) == ["features.json"], "save wrote more than the features file")
    status, _ = call(addr, "GET", "/api/state")
    check(status == 200 and server.poll() is None, "the server is not alive at the end")
finally:
    server.send_signal(signal.SIGTERM)
    check(server.wait(timeout=30) == 0, "the server did not stop cleanly on SIGTERM")

# A new server on the saved file finds the same features and maps them.
server, addr = start(saved)
try:
    state = json.loads(call(addr, "GET", "/api/state")[1])
    check(state["features"]["features"] == feats, "the saved features did not come back")
    check(state["map"] is not None and state["map"]["certificate"]["valid"], "the saved features were not mapped")
finally:
    server.send_signal(signal.SIGTERM)
    server.wait(timeout=30)

if failures:
    sys.exit(f"{len(failures)} failure(s); first: {failures[0]}")
print("serve API: ok")
