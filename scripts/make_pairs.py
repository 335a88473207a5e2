#!/usr/bin/env python3
"""Picks the shipped morph pairs (data/pairs/) the same way on two heads: after turning each head to
face +z with +y up and scaling it into the unit box, each pair is the vertex most extreme in one
direction on both meshes (nose tip = most frontal, crown = highest, ...) and the border pairs are
the border loop's rightmost vertex and three more at equal arc lengths along it. Usage:
  scripts/make_pairs.py SOURCE.off SOURCE_TURN TARGET.off TARGET_TURN OUT.json [SKIP,...]
SKIP names interior pairs to leave out (a face mask has no 'back').
TURN is a permutation with signs taking the mesh's axes to (right, up, front), e.g. "x,z,-y"."""
import json
import sys

def read_off(path):
    words = open(path).read().split()
    n, f = int(words[1]), int(words[2])
    verts = [tuple(map(float, words[4 + 3 * i:7 + 3 * i])) for i in range(n)]
    k, faces = 4 + 3 * n, []
    for _ in range(f):
        c = int(words[k])
        faces.append(tuple(map(int, words[k + 1:k + 1 + c])))
        k += 1 + c
    return verts, faces

def border_loop(faces):
    """The border loop in the faces' orientation."""
    edges = set()
    for f in faces:
        for i in range(len(f)):
            edges.add((f[i], f[(i + 1) % len(f)]))
    nxt = {a: b for (a, b) in edges if (b, a) not in edges}
    loop = [min(nxt)]
    while nxt[loop[-1]] != loop[0]:
        loop.append(nxt[loop[-1]])
    return loop

def turned(verts, turn):
    axes = []
    for t in turn.split(','):
        sign = -1.0 if t.startswith('-') else 1.0
        axes.append((sign, 'xyz'.index(t[-1])))
    pts = [tuple(s * v[i] for s, i in axes) for v in verts]
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    c = [(lo[k] + hi[k]) / 2 for k in range(3)]
    h = max((hi[k] - lo[k]) / 2 for k in range(3))
    return [tuple((p[k] - c[k]) / h for k in range(3)) for p in pts]

# Interior pairs: directions (right, up, front) whose most extreme vertex is the feature.
INTERIOR = {
    'nose_tip': (0, 0, 1), 'crown': (0, 1, 0.2), 'right_side': (1, 0.3, 0), 'left_side': (-1, 0.3, 0),
    'chin': (0, -1, 0.6), 'brow_right': (0.6, 0.6, 0.6), 'brow_left': (-0.6, 0.6, 0.6), 'back': (0, 0.5, -1),
}
BORDER_PAIRS = 4  # border_0 is the loop's rightmost vertex, the others follow at equal arc lengths

def pick(pts, candidates, d):
    return max(candidates, key=lambda i: sum(pts[i][k] * d[k] for k in range(3)))

def main():
    src, src_turn, dst, dst_turn, out = sys.argv[1:6]
    skip = set(sys.argv[6].split(',')) if len(sys.argv) > 6 else set()
    ends = {}
    for side, path, turn in (('source', src, src_turn), ('target', dst, dst_turn)):
        verts, faces = read_off(path)
        pts = turned(verts, turn)
        loop = border_loop(faces)
        on_border = set(loop)
        inner = [i for i in range(len(pts)) if i not in on_border]
        for name, d in INTERIOR.items():
            if name in skip:
                continue
            ends.setdefault(name, {})[side] = {'vertex': pick(pts, inner, d)}
        start = loop.index(pick(pts, loop, (1, 0, 0)))
        loop = loop[start:] + loop[:start]
        dist = lambda a, b: sum((verts[a][k] - verts[b][k]) ** 2 for k in range(3)) ** 0.5
        at = [0.0]
        for a, b in zip(loop, loop[1:] + loop[:1]):
            at.append(at[-1] + dist(a, b))
        for j in range(BORDER_PAIRS):
            want = at[-1] * j / BORDER_PAIRS
            k = min(range(len(loop)), key=lambda i: abs(at[i] - want))
            ends.setdefault('border_%d' % j, {})[side] = {'vertex': loop[k]}
    # A vertex picked twice on either mesh keeps its first pair.
    pairs, used = [], {'source': set(), 'target': set()}
    for n, e in ends.items():
        if e['source']['vertex'] in used['source'] or e['target']['vertex'] in used['target']:
            continue
        used['source'].add(e['source']['vertex'])
        used['target'].add(e['target']['vertex'])
        pairs.append({'name': n, 'source': e['source'], 'target': e['target']})
    with open(out, 'w') as f:
        json.dump({'units': 'mesh', 'pairs': pairs}, f, indent=2)
        f.write('\n')

if __name__ == '__main__':
    main()
