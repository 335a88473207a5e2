#!/usr/bin/env python3
"""Issue 13, must-show 7: the paper's Table 2 beside ours. The real `ctmap map --report` on the
closest meshes we have (closed meshes with two charts, a photo and its mirror image, from
`starter-features --charts 2`; disc heads with the shipped features), time per stage with
`--refine paper` (the paper's pipeline) and with the default (the paper's, then the distortion
optimiser), median of three runs. Written into BENCHMARKS.md between its markers.

    bench/charts_table.py [--build build] [--runs 3] [--markdown BENCHMARKS.md]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

from markdown_section import replace_section

BEGIN = "<!-- charts:begin (bench/charts_table.py writes this section) -->"
END = "<!-- charts:end -->"

# (paper model, its triangles and features as the paper states them, its stage times in s:
#  paths, embedding, refinement, total), then ours: mesh, image, how the features are made.
ROWS = [
    ("Rachel", "?", "?", (1.71125, 0.755625, 0.023625, 2.4905),
     "mannequin-devil", "astronaut", ("starter", 8, 12)),
    ("Igea (two photos)", "4,442", "45, 13 on the seam", (7.011625, 9.179875, 0.77325, 16.96475),
     "homer", "astronaut", ("charts", 13, 16)),
    ("Rabbit (photo + mirror)", "850", "?", (1.2322, 0.562523, 0.01332, 1.808043),
     "bunny00", "chelsea", ("charts", 8, 12)),
    ("Cow (head)", "1,891", "?", (2.959125, 2.508, 0.02925, 5.496375),
     "cow", "chelsea", ("charts", 8, 12)),
    ("Face", "2,923", "?", (2.9475, 3.621, 0.03675, 6.60525),
     "nefertiti", "astronaut", ("shipped", "nefertiti_astronaut.json")),
]


def data_file(rel):
    here = os.path.dirname(os.path.abspath(__file__))
    for d in [os.environ.get("CTMAP_DATA", ""), os.path.join(here, "..", "data"), os.path.join(here, "..", "..", "shared", "data"),
              os.path.join(here, "..", ".cache", "data")]:
        if d and os.path.exists(os.path.join(d, rel)):
            return os.path.join(d, rel)
    sys.exit(f"charts_table: {rel} not found (scripts/fetch_data.sh)")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default="build")
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--markdown", default="BENCHMARKS.md")
    a = p.parse_args()
    ctmap = os.path.join(a.build, "ctmap")
    lines = []
    for paper, paper_t, paper_f, paper_s, mesh, image, how in ROWS:
        mesh_path = data_file(f"meshes/{mesh}.off")
        with tempfile.TemporaryDirectory() as tmp:
            features = os.path.join(tmp, "features.json")
            if how[0] == "charts":
                subprocess.run([ctmap, "starter-features", mesh_path, "--image", data_file(f"images/{image}.png"),
                                "--charts", "2", "--seam", str(how[1]), "--interior", str(how[2]), "-o", features],
                               check=True, stdout=subprocess.DEVNULL)
            elif how[0] == "starter":
                subprocess.run([ctmap, "starter-features", mesh_path, "--image", data_file(f"images/{image}.png"),
                                "--border", str(how[1]), "--interior", str(how[2]), "-o", features],
                               check=True, stdout=subprocess.DEVNULL)
            else:
                features = data_file(f"features/{how[1]}")
            chart_file = json.load(open(features))
            out = {}
            for refine in ("paper", "isometric"):
                reports = []
                for _ in range(a.runs):
                    report = os.path.join(tmp, "r.json")
                    subprocess.run([ctmap, "map", mesh_path, features, "-o", os.path.join(tmp, "m.obj"), "--refine",
                                    refine, "--report", report, "-q"], check=True)
                    reports.append(json.load(open(report)))
                t = {k: statistics.median(r["timings_ms"][k] for r in reports) / 1000 for k in reports[0]["timings_ms"]}
                out[refine] = (t, reports[0])
        tp, r = out["paper"]
        ti, ri = out["isometric"]
        assert r["certificate"]["valid"] and ri["certificate"]["valid"], mesh
        if "charts" in r:
            faces = r["counts"]["input_faces"]
            nfeat = len({f["name"] for c in chart_file["charts"] for f in c["features"]})
            seam = len(chart_file["charts"][0]["border"])
            feats = f"{nfeat} in 2 charts, {seam} on the seam"
            sd = " / ".join(f"{c['certificate']['symmetric_dirichlet'] / 4:.2f}" for c in ri["charts"])
        else:
            faces = r["counts"]["input_faces"]
            feats = str(r["counts"]["features"])
            sd = f"{ri['certificate']['symmetric_dirichlet'] / 4:.2f}"
        ps = " / ".join(f"{x:.2f}" for x in paper_s)
        lines.append(f"| {paper}: {paper_t} t, {paper_f} | {ps} | {mesh}: {faces:,} t, {feats} | "
                     f"{tp['paths']:.3f} | {tp['embed']:.3f} | {tp['refine']:.3f} | {tp['total']:.3f} | "
                     f"{ti['optimise']:.3f} | {ti['total']:.3f} | {sd} |")
        print(lines[-1], file=sys.stderr)
    cmd = f"python3 bench/charts_table.py --runs {a.runs}"
    section = "\n".join([
        BEGIN,
        "## Charts: the paper's Table 2 beside ours (issue 13)",
        "",
        f"`{cmd}` — the real `ctmap map --report`, median of {a.runs} runs, seconds of wall time on this "
        "2-core machine (the paper: a Pentium IV 2.0 GHz). The paper's models are not available; each row "
        "puts the closest mesh we have beside it. The closed meshes get two charts, a photo and its mirror "
        "image, from `ctmap starter-features --charts 2` (homer with 13 seam features and 45 in all, as the "
        "paper's Igea); the disc heads their starter or shipped features. `paths` includes tracing the seams; "
        "`refine` is the paper's relaxation (§2.4), `optimise` the distortion optimiser the default adds. "
        "Every map is certified. The paper gives paths / embedding / refinement / total.",
        "",
        "| paper model | paper s | ours | paths | embed | refine | total (`--refine paper`) | optimise | total (default) | symmetric Dirichlet / 4 per chart (default) |",
        "|---|---|---|---|---|---|---|---|---|---|",
        *lines,
        END,
    ])
    replace_section(a.markdown, BEGIN, END, section)


if __name__ == "__main__":
    main()
