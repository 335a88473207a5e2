"""What the operators do, without UI: the object as ctmap's arrays, the features as ctmap's dicts
and features.json, the map, and its two results (a new object; the photo baked into the object's
own UVs). Every function leaves the scene as it was when it raises."""
import json
import os

import bpy
import numpy as np

from . import module_finder


def ctmap():
    return module_finder.load()


def mesh_arrays(obj):
    """(V, F, UV): the object's vertices (its own coordinates, Blender's order), its triangles
    (n-gons split as Blender's loop triangles) and, when it has a UV map, the active one's UVs per
    triangle corner (m x 3 x 2; None without)."""
    me = obj.data
    me.calc_loop_triangles()
    V = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", V)
    tri = me.loop_triangles
    F = np.empty(len(tri) * 3, dtype=np.int64)
    tri.foreach_get("vertices", F)
    UV = None
    if me.uv_layers.active is not None:
        loops = np.empty(len(tri) * 3, dtype=np.int64)
        tri.foreach_get("loops", loops)
        uv = np.empty(len(me.loops) * 2)
        me.uv_layers.active.data.foreach_get("uv", uv)
        UV = uv.reshape(-1, 2)[loops].reshape(-1, 3, 2)
    return V.reshape(-1, 3), F.reshape(-1, 3), UV


def photo_size(image):
    if image is None:
        raise ValueError("no photo: choose the image the features are placed on (ctmap panel, Photo)")
    w, h = image.size
    if w == 0 or h == 0:
        raise ValueError(f"the photo '{image.name}' has no pixels (is its file {image.filepath!r} missing?)")
    return int(w), int(h)


def photo_array(image):
    """The photo as an H x W x 4 uint8 array, rows top to bottom (Blender stores them bottom up)."""
    w, h = photo_size(image)
    px = np.empty(w * h * image.channels, dtype=np.float32)
    image.pixels.foreach_get(px)
    a = px.reshape(h, w, image.channels)[::-1]
    if image.channels == 3:
        a = np.concatenate([a, np.ones((h, w, 1), np.float32)], axis=2)
    return np.clip(np.round(a[:, :, :4] * 255), 0, 255).astype(np.uint8)


def features_of(obj):
    """The object's features as ctmap's dicts (image points in pixels)."""
    out = []
    for f in obj.ctmap.features:
        d = {"name": f.name, "image": [float(f.image[0]), float(f.image[1])]}
        if f.use_point:
            d["point"] = [float(x) for x in f.point]
        else:
            d["vertex"] = int(f.vertex)
        out.append(d)
    return out


def read_features_file(path, image_size):
    """features.json (the CLI's format, README) as a list of dicts with image points in pixels."""
    with open(path) as fh:
        doc = json.load(fh)
    return features_of_doc(doc, path, image_size)


def features_of_doc(doc, path, image_size):
    """A features file's (or one chart's) features, image points in pixels; `path` names it in errors."""
    if not isinstance(doc, dict) or not isinstance(doc.get("features"), list):
        raise ValueError(f"{path}: not a features file (no \"features\" list)")
    units = doc.get("units", "pixels")
    size = doc.get("image_size", image_size)
    out = []
    for i, f in enumerate(doc["features"]):
        if not isinstance(f, dict) or "name" not in f or "image" not in f or ("vertex" in f) == ("point" in f):
            raise ValueError(f"{path}: feature #{i} needs a name, an image point and a vertex or a point")
        x, y = (float(v) for v in f["image"])
        if units == "uv":
            if not size:
                raise ValueError(f"{path}: image points in UV need the photo's size")
            x, y = x * size[0], (1 - y) * size[1]
        d = {"name": str(f["name"]), "image": [x, y]}
        if "vertex" in f:
            d["vertex"] = int(f["vertex"])
        else:
            d["point"] = [float(v) for v in f["point"]]
        out.append(d)
    return out


def read_charts_file(path):
    """A features file with "charts" (README, charts): per chart its name, photo (an absolute path),
    image size, border names and features (image points in pixels)."""
    with open(path) as fh:
        doc = json.load(fh)
    if not isinstance(doc, dict) or not isinstance(doc.get("charts"), list) or not doc["charts"]:
        raise ValueError(f"{path}: not a charts file (no \"charts\" list)")
    base = os.path.dirname(os.path.abspath(path))
    charts = []
    for i, ch in enumerate(doc["charts"]):
        if not isinstance(ch, dict) or "name" not in ch or "image" not in ch or "features" not in ch:
            raise ValueError(f"{path}: chart #{i} needs a name, an image and features")
        image = os.path.normpath(os.path.join(base, ch["image"]))
        size = ch.get("image_size")
        if not size:
            img = bpy.data.images.load(image, check_existing=True)
            size = list(img.size)
        feats = features_of_doc({"units": doc.get("units", "pixels"), "image_size": size, "features": ch["features"]},
                                f"{path}, chart '{ch['name']}'", size)
        charts.append({"name": str(ch["name"]), "image": image, "image_size": [int(size[0]), int(size[1])],
                       "border": [str(b) for b in ch.get("border", [])], "features": feats})
    return charts


def is_charts_file(path):
    with open(path) as fh:
        doc = json.load(fh)
    return isinstance(doc, dict) and "charts" in doc


def write_features_file(path, features, image_size, image_path=""):
    doc = {"units": "pixels", "image_size": list(image_size), "features": features}
    if image_path:
        doc["image"] = image_path
    tmp = path + ".tmp"
    with open(tmp, "w") as fh:
        json.dump(doc, fh, indent=1)
    os.replace(tmp, path)


def set_features(obj, features):
    obj.ctmap.features.clear()
    for d in features:
        f = obj.ctmap.features.add()
        f.name = d["name"]
        f.image = d["image"]
        if "point" in d:
            f.use_point, f.point = True, d["point"]
        else:
            f.vertex = d["vertex"]


def prepare_map(obj, settings):
    """What ctmap.map_texture (or, for an object with charts, ctmap.map_charts) needs, read from
    Blender's data (on Blender's thread: bpy is not thread-safe). Raises ValueError when something
    is missing."""
    if obj is None or obj.type != 'MESH':
        raise ValueError("select a mesh object")
    V, F, _ = mesh_arrays(obj)
    if obj.ctmap.charts_json:
        charts = json.loads(obj.ctmap.charts_json)
        return dict(V=V, F=F, charts=charts, refine=settings.refine, border_mode=settings.border_mode)
    size = photo_size(settings.image)
    feats = features_of(obj)
    if not feats:
        raise ValueError(f"'{obj.name}' has no features: add some (ctmap panel, Add feature) or import features.json")
    return dict(V=V, F=F, features=feats, image_size=size, refine=settings.refine, border=settings.border,
                border_mode=settings.border_mode)


def compute_map(args):
    """The map itself (numpy arrays in and out, no bpy: any thread). Raises ValueError with ctmap's message."""
    if "charts" in args:
        return ctmap().map_charts(args["V"], args["F"], args["charts"], refine=args["refine"],
                                  border_mode=args["border_mode"])
    return ctmap().map_texture(args["V"], args["F"], args["features"], image_size=args["image_size"],
                               refine=args["refine"], border=args["border"], border_mode=args["border_mode"])


def run_map(obj, settings):
    return compute_map(prepare_map(obj, settings))


def photo_material(name, image):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    bsdf = next(n for n in nodes if n.type == 'BSDF_PRINCIPLED')
    bsdf.inputs["Specular"].default_value = 0.0  # a photo: its colours, no highlight over them
    bsdf.inputs["Roughness"].default_value = 1.0
    tex = nodes.new("ShaderNodeTexImage")
    tex.image = image
    tex.location = (-400, 200)
    mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    return mat


def make_object(context, obj, result, image):
    """Result (a): a new object with the mapped mesh (the input's vertices first, then the ones the
    cut inserted), its UV map and a material with the photo; placed like `obj`."""
    V, F, UVc = result["V"], result["F"], result["UV_corners"]
    me = bpy.data.meshes.new(obj.name + "_ctmap")
    me.from_pydata([tuple(v) for v in V], [], [tuple(int(i) for i in f) for f in F])
    uv = me.uv_layers.new(name="ctmap")
    # from_pydata keeps the faces' order and their corners' order: loop 3f + k is corner k of face f.
    uv.data.foreach_set("uv", np.asarray(UVc, dtype=np.float64).reshape(-1))
    if "chart_names" in result:  # charts: a material per chart with its own photo, the rest untextured
        charts = json.loads(obj.ctmap.charts_json)
        for i, name in enumerate(result["chart_names"]):
            img = bpy.data.images.load(charts[i]["image"], check_existing=True) if i < len(charts) else None
            me.materials.append(photo_material(f"{obj.name}_ctmap_{name}", img))
        me.polygons.foreach_set("material_index", np.asarray(result["chart"], dtype=np.int32))
    else:
        me.materials.append(photo_material(obj.name + "_ctmap", image))
    me.update()
    new = bpy.data.objects.new(obj.name + "_ctmap", me)
    new.matrix_world = obj.matrix_world.copy()
    for coll in obj.users_collection:
        coll.objects.link(new)
    return new


def bake_into(obj, result, image, size=0):
    """Result (b): the photo baked into the object's own UVs (ctmap.bake) as a new image on a
    material of the object itself; its vertices, faces and UVs are not touched."""
    V, F, UV = mesh_arrays(obj)
    if UV is None:
        raise ValueError(f"'{obj.name}' has no UV map to bake into: choose Result: New object")
    if "chart_names" in result:  # a photo per chart; the rest (faces in no chart) mid grey
        charts = json.loads(obj.ctmap.charts_json)
        photo = [photo_array(bpy.data.images.load(ch["image"], check_existing=True)) for ch in charts]
        if len(result["chart_names"]) > len(charts):
            photo.append(np.full((1, 1, 4), 128, np.uint8))
        image = bpy.data.images.load(charts[0]["image"], check_existing=True)
    else:
        photo = photo_array(image)
    sz = (size, size) if size > 0 else None
    b = ctmap().bake(result, photo, V, F, UV, size=sz)
    h, w = b["texture"].shape[:2]
    baked = bpy.data.images.new(obj.name + "_ctmap_baked", width=w, height=h, alpha=True)  # (size: the first photo's)
    baked.pixels.foreach_set((b["texture"][::-1].astype(np.float32) / 255.0).reshape(-1))
    baked.pack()
    mat = photo_material(obj.name + "_ctmap_baked", baked)
    if len(obj.material_slots) == 0:
        obj.data.materials.append(mat)
    else:
        for slot in obj.material_slots:  # the object's own slots: the mesh's materials stay as they were
            slot.link = 'OBJECT'
            slot.material = mat
    return baked, b


def certificate_text(result):
    c = result["certificate"]
    state = "valid" if c.get("valid") else "INVALID"
    d = c.get("distortion", c)
    sd = d.get("symmetric_dirichlet")
    return (f"{state}: {c.get('flipped', 0)} flipped, feature error {c.get('feature_max_error', 0):.2g}, "
            + (f"symmetric Dirichlet {sd:.3f}, " if sd is not None else "")
            + f"{len(result['F'])} triangles" + (f", charts {', '.join(result['chart_names'])}" if "chart_names" in result else ""))
