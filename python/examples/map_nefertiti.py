#!/usr/bin/env python3
"""Maps the shipped example (nefertiti.off with the features of nefertiti_astronaut.json on
astronaut.png) from Python and plots its UV layout over the photograph with matplotlib.

    PYTHONPATH=build/python python3 python/examples/map_nefertiti.py [--data ../shared/data] [-o uv.png]
"""
import argparse
import json
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import LineCollection

import ctmap


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data"))
    p.add_argument("-o", "--output", default="nefertiti_uv.png")
    a = p.parse_args()
    V, F = ctmap.read_mesh(os.path.join(a.data, "meshes", "nefertiti.off"))
    features = json.load(open(os.path.join(a.data, "features", "nefertiti_astronaut.json")))["features"]
    photo = plt.imread(os.path.join(a.data, "images", "astronaut.png"))
    h, w = photo.shape[:2]
    r = ctmap.map_texture(V, F, features, image_size=(w, h))
    print(f"{len(r['F'])} triangles, certificate valid: {r['certificate']['valid']}, "
          f"flipped: {r['certificate']['flipped']}")
    # UV (OBJ's convention, v up) to pixels (y down): x = u W, y = (1 - v) H.
    px = r["UV"] * [w, -h] + [0, h]
    edges = px[r["F"][:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)]
    fig, ax = plt.subplots(figsize=(7, 7))
    ax.imshow(photo)
    ax.add_collection(LineCollection(edges, colors="white", linewidths=0.3, alpha=0.8))
    fv = r["feature_vertex"]
    ax.plot(px[fv, 0], px[fv, 1], "o", color="red", markersize=4)
    ax.set_axis_off()
    fig.savefig(a.output, dpi=100, bbox_inches="tight")
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
