#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpus, fuzz/corpus/<target>/ (README.md).

Seeds are small on purpose (libFuzzer mutates small inputs fastest; the committed corpus stays a
few KB per target): a patch of the example mesh nefertiti.off (../shared/data, or $CTMAP_DATA)
written in every mesh format, hand-made files for the formats' variants, the project's features
files, and tiny PNG/JPEG images. JPEGs are encoded by stb_image_write (the C compiler and Debian's
libstb), everything else by this script. Usage: python3 fuzz/make_seeds.py
"""
import base64
import json
import os
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"


def data_dir():
    for d in (os.environ.get("CTMAP_DATA"), ROOT.parent / "shared" / "data", ROOT / ".cache" / "data"):
        if d and (pathlib.Path(d) / "meshes" / "nefertiti.off").exists():
            return pathlib.Path(d)
    sys.exit("make_seeds: nefertiti.off not found (set CTMAP_DATA, or run scripts/fetch_data.sh)")


def read_off(path):
    words = [w for line in path.read_text().splitlines() for w in line.split("#")[0].split()]
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(w) for w in words[at:at + 3]))
        at += 3
    faces = []
    for _ in range(nf):
        n = int(words[at])
        faces.append(tuple(int(w) for w in words[at + 1:at + 1 + n]))
        at += 1 + n
    return verts, faces


def patch(verts, faces, nfaces):
    """The first `nfaces` faces and the vertices they use, renumbered in order of use."""
    remap, out_v, out_f = {}, [], []
    for f in faces[:nfaces]:
        for v in f:
            if v not in remap:
                remap[v] = len(out_v)
                out_v.append(verts[v])
        out_f.append(tuple(remap[v] for v in f))
    return out_v, out_f


TETRA_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TETRA_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
# A square of four quads around a centre vertex (polygons with 4 corners are triangulated on read),
# and one pentagon.
GRID_V = [(x, y, 0.1 * x * y) for y in (0, 1, 2) for x in (0, 1, 2)]
GRID_F = [(0, 1, 4, 3), (1, 2, 5, 4), (3, 4, 7, 6), (4, 5, 8, 7)]
PENTA_V = [(1, 0, 0), (0.31, 0.95, 0), (-0.81, 0.59, 0), (-0.81, -0.59, 0), (0.31, -0.95, 0)]
PENTA_F = [(0, 1, 2, 3, 4)]


def fmt(x):
    return repr(float(x))


def off_text(v, f, header="OFF"):
    lines = [header, f"{len(v)} {len(f)} 0"]
    lines += [" ".join(fmt(c) for c in p) for p in v]
    lines += [" ".join(str(i) for i in (len(face),) + face) for face in f]
    return "\n".join(lines) + "\n"


def obj_text(v, f, uv=False, normals=False, negative=False):
    lines = ["# ctmap fuzz seed", "o seed"]
    lines += ["v " + " ".join(fmt(c) for c in p) for p in v]
    if uv:
        lines += [f"vt {fmt(p[0] * 0.5 + 0.25)} {fmt(p[1] * 0.5 + 0.25)}" for p in v]
    if normals:
        lines += ["vn 0 0 1"]
    for face in f:
        corners = []
        for i in face:
            k = i - len(v) if negative else i + 1
            if uv and normals:
                corners.append(f"{k}/{k}/1")
            elif uv:
                corners.append(f"{k}/{k}")
            elif normals:
                corners.append(f"{k}//1")
            else:
                corners.append(str(k))
        lines.append("f " + " ".join(corners))
    return "\n".join(lines) + "\n"


def ply_ascii(v, f, extra=False):
    head = ["ply", "format ascii 1.0", "comment ctmap fuzz seed", f"element vertex {len(v)}",
            "property float x", "property float y", "property float z"]
    if extra:
        head += ["property uchar red", "property uchar green", "property uchar blue"]
    head += [f"element face {len(f)}", "property list uchar int vertex_indices", "end_header"]
    body = [" ".join(fmt(c) for c in p) + (" 200 100 50" if extra else "") for p in v]
    body += [" ".join(str(i) for i in (len(face),) + face) for face in f]
    return ("\n".join(head + body) + "\n").encode()


def ply_binary(v, f, endian="<", double=False, index_type="int"):
    name = "binary_little_endian" if endian == "<" else "binary_big_endian"
    ctype, cfmt = ("double", "d") if double else ("float", "f")
    ifmt = {"int": "i", "uint": "I", "short": "h"}[index_type]
    head = (f"ply\nformat {name} 1.0\nelement vertex {len(v)}\n"
            f"property {ctype} x\nproperty {ctype} y\nproperty {ctype} z\n"
            f"element face {len(f)}\nproperty list uchar {index_type} vertex_indices\nend_header\n").encode()
    body = b"".join(struct.pack(endian + cfmt * 3, *p) for p in v)
    body += b"".join(struct.pack(endian + "B" + ifmt * len(face), len(face), *face) for face in f)
    return head + body


def tri_faces(f):
    return [t for face in f for t in ((face[0], face[k], face[k + 1]) for k in range(1, len(face) - 1))]


def stl_ascii(v, f):
    lines = ["solid seed"]
    for a, b, c in tri_faces(f):
        lines += ["  facet normal 0 0 1", "    outer loop"]
        lines += [f"      vertex {' '.join(fmt(x) for x in v[i])}" for i in (a, b, c)]
        lines += ["    endloop", "  endfacet"]
    lines.append("endsolid seed")
    return "\n".join(lines) + "\n"


def stl_binary(v, f):
    tris = tri_faces(f)
    out = b"ctmap fuzz seed".ljust(80, b" ") + struct.pack("<I", len(tris))
    for a, b, c in tris:
        out += struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *v[i]) for i in (a, b, c)) + b"\0\0"
    return out


def png(width, height, color_type, bit_depth=8, palette=None):
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[color_type]
    bpp = channels * bit_depth // 8 or 1
    rows = b""
    for y in range(height):
        row = bytearray()
        for x in range(width):
            for c in range(channels):
                val = (x * 37 + y * 91 + c * 53) & 0xFF
                row += bytes([val, val ^ 0x5A]) if bit_depth == 16 else bytes([val % (len(palette) if palette else 256)])
        # Rows use filters 0..4 in turn, so the seed exercises each of PNG's filters.
        ftype = y % 5
        prev = rows_raw[-1] if y else bytes(len(row))
        filtered = bytearray()
        for i, b in enumerate(row):
            a = row[i - bpp] if i >= bpp else 0
            up = prev[i]
            ul = prev[i - bpp] if i >= bpp else 0
            if ftype == 0:
                p = 0
            elif ftype == 1:
                p = a
            elif ftype == 2:
                p = up
            elif ftype == 3:
                p = (a + up) // 2
            else:
                pa, pb, pc = abs(up - ul), abs(a - ul), abs(a + up - 2 * ul)
                p = a if pa <= pb and pa <= pc else (up if pb <= pc else ul)
            filtered.append((b - p) & 0xFF)
        rows_raw.append(bytes(row))
        rows += bytes([ftype]) + bytes(filtered)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, 0))
    if palette:
        out += chunk(b"PLTE", b"".join(bytes(c) for c in palette))
        out += chunk(b"tRNS", bytes([255, 128]))
    out += chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
    return out


rows_raw = []


def make_png(*args, **kw):
    rows_raw.clear()
    return png(*args, **kw)


JPEG_WRITER = r"""
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#include <stdlib.h>
int main(int argc, char** argv) {
    /* argv: out.jpg width height channels quality */
    int w = atoi(argv[2]), h = atoi(argv[3]), n = atoi(argv[4]), q = atoi(argv[5]);
    unsigned char* p = malloc(w * h * n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < n; ++c) p[(y * w + x) * n + c] = (unsigned char)(x * 29 + y * 71 + c * 97);
    return !stbi_write_jpg(argv[1], w, h, n, p, q);
}
"""


def jpegs():
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if not cc:
        print("make_seeds: no C compiler, no JPEG seeds", file=sys.stderr)
        return {}
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        src, exe = pathlib.Path(tmp) / "w.c", pathlib.Path(tmp) / "w"
        src.write_text(JPEG_WRITER)
        subprocess.run([cc, "-O1", "-w", "-o", str(exe), str(src), "-lm"], check=True)
        for name, args in {"rgb_q90.jpg": (16, 16, 3, 90), "gray_q50.jpg": (9, 7, 1, 50),
                           "rgba_q100.jpg": (17, 3, 4, 100)}.items():
            path = pathlib.Path(tmp) / name
            subprocess.run([str(exe), str(path)] + [str(a) for a in args], check=True)
            out[name] = path.read_bytes()
    return out


def glb(v, f, with_uv=True, texture=None):
    """A binary glTF as ctmap's write_glb lays it out: float positions (and UVs), uint32 indices,
    optionally a PNG embedded through a buffer view."""
    tris = tri_faces(f)
    pos = b"".join(struct.pack("<3f", *p) for p in v)
    idx = b"".join(struct.pack("<3I", *t) for t in tris)
    uv = b"".join(struct.pack("<2f", p[0], 1 - p[1]) for p in v) if with_uv else b""
    blobs, views = [], []

    def add(data, target=None):
        off = sum(len(b) for b in blobs)
        blobs.append(data + b"\0" * (-len(data) % 4))
        view = {"buffer": 0, "byteOffset": off, "byteLength": len(data)}
        if target:
            view["target"] = target
        views.append(view)
        return len(views) - 1

    lo = [min(p[k] for p in v) for k in range(3)]
    hi = [max(p[k] for p in v) for k in range(3)]
    accessors = [{"bufferView": add(pos, 34962), "componentType": 5126, "count": len(v), "type": "VEC3",
                  "min": lo, "max": hi},
                 {"bufferView": add(idx, 34963), "componentType": 5125, "count": 3 * len(tris), "type": "SCALAR"}]
    attributes = {"POSITION": 0}
    if with_uv:
        accessors.append({"bufferView": add(uv, 34962), "componentType": 5126, "count": len(v), "type": "VEC2"})
        attributes["TEXCOORD_0"] = 2
    doc = {"asset": {"version": "2.0", "generator": "ctmap fuzz seed"}, "scene": 0, "scenes": [{"nodes": [0]}],
           "nodes": [{"mesh": 0}],
           "meshes": [{"name": "ctmap", "primitives": [{"attributes": attributes, "indices": 1, "mode": 4}]}]}
    if texture:
        doc["images"] = [{"bufferView": add(texture), "mimeType": "image/png"}]
        doc["samplers"] = [{"magFilter": 9729, "minFilter": 9987}]
        doc["textures"] = [{"sampler": 0, "source": 0}]
        doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        doc["meshes"][0]["primitives"][0]["material"] = 0
    binary = b"".join(blobs)
    doc["buffers"] = [{"byteLength": len(binary)}]
    doc["accessors"], doc["bufferViews"] = accessors, views
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body, doc, binary


def gltf_text(glb_doc, binary):
    doc = json.loads(json.dumps(glb_doc))
    doc["buffers"] = [{"byteLength": len(binary),
                       "uri": "data:application/octet-stream;base64," + base64.b64encode(binary).decode()}]
    return json.dumps(doc, indent=1).encode()


def main():
    data = data_dir()
    nv, nf = read_off(data / "meshes" / "nefertiti.off")
    pv, pf = patch(nv, nf, 24)
    seeds = {
        "fuzz_off": {
            "nefertiti_patch.off": off_text(pv, pf),
            "tetra.off": off_text(TETRA_V, TETRA_F),
            "grid_quads.off": off_text(GRID_V, GRID_F),
            "pentagon.off": off_text(PENTA_V, PENTA_F),
            "comments.off": "OFF # header comment\n# a comment line\n\n4 4 6\n0 0 0\n1 0 0 # x\n0 1 0\n0 0 1\n"
                            "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
            "coff.off": "COFF\n4 4 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n0 0 1 9 9 9 255\n"
                        "3 0 2 1 1 0 0\n3 0 1 3\n3 0 3 2\n3 1 2 3\n",
            "noff.off": "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
            "header_on_one_line.off": "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        },
        "fuzz_obj": {
            "nefertiti_patch.obj": obj_text(pv, pf),
            "tetra_uv_normals.obj": obj_text(TETRA_V, TETRA_F, uv=True, normals=True),
            "grid_quads_negative.obj": obj_text(GRID_V, GRID_F, negative=True),
            "pentagon_normals.obj": obj_text(PENTA_V, PENTA_F, normals=True),
        },
        "fuzz_ply": {
            "nefertiti_patch_ascii.ply": ply_ascii(pv, pf),
            "tetra_colors_ascii.ply": ply_ascii(TETRA_V, TETRA_F, extra=True),
            "tetra_le.ply": ply_binary(TETRA_V, TETRA_F),
            "grid_be_double_uint.ply": ply_binary(GRID_V, GRID_F, endian=">", double=True, index_type="uint"),
            "pentagon_le_short.ply": ply_binary(PENTA_V, PENTA_F, index_type="short"),
        },
        "fuzz_stl": {
            "nefertiti_patch_ascii.stl": stl_ascii(pv, pf[:8]),
            "tetra_ascii.stl": stl_ascii(TETRA_V, TETRA_F),
            "tetra_binary.stl": stl_binary(TETRA_V, TETRA_F),
            "grid_binary.stl": stl_binary(GRID_V, GRID_F),
        },
        "fuzz_textured_obj": {
            "nefertiti_patch_uv.obj": "mtllib seed.mtl\nusemtl textured\n" + obj_text(pv, pf, uv=True),
            "tetra_uv_normals.obj": obj_text(TETRA_V, TETRA_F, uv=True, normals=True),
            "grid_uv_negative.obj": "mtllib a.mtl\ng patch_0\n" + obj_text(GRID_V, GRID_F, uv=True, negative=True),
            "pentagon_vn.obj": obj_text(PENTA_V, PENTA_F, normals=True),
            "plain.obj": obj_text(TETRA_V, TETRA_F),
        },
        "fuzz_features": {},
        "fuzz_pairs": {},
        "fuzz_image": {},
        "fuzz_glb": {},
        "fuzz_gltf": {},
    }
    for p in sorted((ROOT / "data" / "features").glob("*.json")) + sorted((data / "features").glob("*.json")):
        seeds["fuzz_features"].setdefault(p.name, p.read_bytes())
    seeds["fuzz_features"]["points_uv.json"] = json.dumps({
        "image": "texture.png", "units": "uv",
        "features": [{"name": "a", "vertex": 0, "image": [0.25, 0.5]},
                     {"name": "b", "point": [0.1, 0.2, 0.3], "image": [0.75, 0.5]},
                     {"name": "c", "vertex": 2, "image": [0.5, 1.0]}]}, indent=1)
    for p in sorted((ROOT / "data" / "pairs").glob("*.json")):
        seeds["fuzz_pairs"][p.name] = p.read_bytes()
    seeds["fuzz_pairs"]["points.json"] = json.dumps({
        "units": "mesh",
        "pairs": [{"name": "p", "source": {"point": [0.1, -0.2, 3e-5]}, "target": {"vertex": 4}},
                  {"name": "q", "source": {"vertex": 2}, "target": {"point": [1, 2, 3]}}]}, indent=1)
    tiny_png = make_png(2, 2, 2)
    seeds["fuzz_image"].update({
        "rgb_8x8.png": make_png(8, 8, 2), "rgba_5x3.png": make_png(5, 3, 6), "gray_7x2.png": make_png(7, 2, 0),
        "gray_alpha_3x3.png": make_png(3, 3, 4), "rgb16_4x4.png": make_png(4, 4, 2, bit_depth=16),
        "palette_6x6.png": make_png(6, 6, 3, palette=[(255, 0, 0), (0, 255, 0), (0, 0, 255), (9, 9, 9)]),
    })
    seeds["fuzz_image"].update(jpegs())
    for name, (v, f, uv, tex) in {"nefertiti_patch": (pv, pf, True, None), "tetra_textured": (TETRA_V, TETRA_F, True, tiny_png),
                                  "grid_no_uv": (GRID_V, GRID_F, False, None)}.items():
        binary_glb, doc, binary = glb(v, f, uv, tex)
        seeds["fuzz_glb"][name + ".glb"] = binary_glb
        seeds["fuzz_gltf"][name + ".gltf"] = gltf_text(doc, binary)

    if CORPUS.exists():
        shutil.rmtree(CORPUS)
    total = 0
    for target, files in seeds.items():
        d = CORPUS / target
        d.mkdir(parents=True)
        for name, content in files.items():
            (d / name).write_bytes(content.encode() if isinstance(content, str) else content)
            total += len(content)
        print(f"{target}: {len(files)} seeds")
    print(f"corpus: {total} bytes in {CORPUS.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
