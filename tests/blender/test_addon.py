"""The Blender add-on, headless (issue 44 must-shows 1, 2 and 4), run by CTest (tests/CMakeLists.txt,
BlenderAddon):
    blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py -- \\
        ADDON.zip CTMAP_BIN OUT_DIR [RENDER.png]
Installs and enables the add-on from its zip in a fresh profile (BLENDER_USER_* set by CTest), makes
nefertiti, loads the astronaut photo, imports the shipped features, and runs Map both ways:
(a) a new object whose UV map holds every feature at its image point, exported as OBJ and passed
by `ctmap check`; (b) baked into the object's own UVs, the object's vertices, order and UVs
unchanged, the image equal to `ctmap bake`'s for the same inputs. Then a feature added by the
operator, and an invalid layout that leaves the scene unchanged with the CLI's message."""
import os
import subprocess
import sys
import traceback

import bpy
import mathutils
import numpy as np

args = sys.argv[sys.argv.index("--") + 1:]
ZIP, CTMAP, OUT = args[:3]
RENDER = args[3] if len(args) > 3 else ""
os.makedirs(OUT, exist_ok=True)
SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def data(rel):
    """A data file, found where the other tests look ($CTMAP_DATA, data/, ../shared/data, .cache/data)."""
    for d in (os.environ.get("CTMAP_DATA"), os.path.join(SRC, "data"), os.path.join(SRC, "..", "shared", "data"),
              os.path.join(SRC, ".cache", "data")):
        if d and os.path.isfile(os.path.join(d, rel)):
            return os.path.join(d, rel)
    raise FileNotFoundError(rel)


MESH = data("meshes/nefertiti.off")
PHOTO = data("images/astronaut.png")
FEATURES = data("features/nefertiti_astronaut.json")
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def read_off(path):
    words = open(path).read().split()
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    vals = words[4:]
    V = [tuple(float(x) for x in vals[3 * i:3 * i + 3]) for i in range(nv)]
    F, o = [], 3 * nv
    for _ in range(nf):
        n = int(vals[o])
        F.append(tuple(int(x) for x in vals[o + 1:o + 1 + n]))
        o += n + 1
    return V, F


def make_object(name, V, F, uv=None):
    me = bpy.data.meshes.new(name)
    me.from_pydata(V, [], F)
    if uv is not None:
        layer = me.uv_layers.new(name="UVMap")
        for poly in me.polygons:
            for li in poly.loop_indices:
                layer.data[li].uv = uv[me.loops[li].vertex_index]
    me.update()
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def activate(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def scene_state():
    return sorted(o.name for o in bpy.data.objects), sorted(i.name for i in bpy.data.images), \
        sorted(m.name for m in bpy.data.materials)


def main():
    # Must-show 4: installable from the zip in a fresh profile (an earlier run's copy removed first).
    scripts = os.environ.get("BLENDER_USER_SCRIPTS")
    if scripts:
        import shutil
        shutil.rmtree(os.path.join(scripts, "addons", "ctmap_addon"), ignore_errors=True)
    bpy.ops.preferences.addon_install(filepath=ZIP, overwrite=True)
    bpy.ops.preferences.addon_enable(module="ctmap_addon")
    check("ctmap_addon" in bpy.context.preferences.addons, "the add-on is installed from its zip and enabled")
    check(hasattr(bpy.ops.ctmap, "map") and hasattr(bpy.types.Object, "ctmap"), "its operators and properties are registered")
    from ctmap_addon import module_finder
    ctmap = module_finder.load()  # the module inside the add-on's folder
    check(os.path.dirname(ctmap.__file__) == os.path.dirname(module_finder.__file__), "the add-on uses the module in its own folder")

    V, F = read_off(MESH)
    obj = make_object("nefertiti", V, F)
    activate(obj)
    photo = bpy.data.images.load(PHOTO)
    s = bpy.context.scene.ctmap
    s.image = photo
    W, H = photo.size
    r = bpy.ops.ctmap.import_features(filepath=FEATURES)
    check(r == {'FINISHED'} and len(obj.ctmap.features) == 16, f"16 features imported ({len(obj.ctmap.features)})")

    # Mode (a): a new object with the map.
    s.result = 'new_object'
    r = bpy.ops.ctmap.map()
    new = bpy.data.objects.get("nefertiti_ctmap")
    check(r == {'FINISHED'} and new is not None, f"Map (a) made a new object: {s.report}")
    me = new.data
    uv = me.uv_layers["ctmap"].data
    worst = 0.0
    for f in obj.ctmap.features:
        want = np.array([f.image[0] / W, 1 - f.image[1] / H])
        for loop in me.loops:
            if loop.vertex_index == f.vertex:  # the map's vertex i is the input's vertex i
                worst = max(worst, float(np.abs(np.array(uv[loop.index].uv) - want).max()))
    check(worst <= 1e-6, f"every feature at its image point in the new UV map (worst {worst:.2e}: Blender's float32 UVs)")
    check("valid" in s.report and "INVALID" not in s.report and "symmetric Dirichlet" in s.report,
          f"the certificate and the distortion in the panel: {s.report}")
    activate(new)
    out_obj = os.path.join(OUT, "mapped.obj")
    bpy.ops.wm.obj_export(filepath=out_obj, export_selected_objects=True, export_uv=True, export_normals=False,
                          export_materials=False, export_triangulated_mesh=True)
    c = subprocess.run([CTMAP, "check", out_obj, "--features", FEATURES, "--image", PHOTO, "--feature-tolerance", "1e-6"],
                       capture_output=True, text=True)
    check(c.returncode == 0 and ": valid" in c.stdout, "the new object exported by Blender passes ctmap check: " +
          (c.stdout + c.stderr).strip().splitlines()[0])

    # Mode (b): the photo baked into an object's own UVs.
    lo, hi = np.min(V, axis=0), np.max(V, axis=0)
    layout = [(0.05 + 0.9 * (v[0] - lo[0]) / (hi[0] - lo[0]), 0.05 + 0.9 * (v[1] - lo[1]) / (hi[1] - lo[1])) for v in V]
    own = make_object("nefertiti_uv", V, F, layout)
    own.ctmap.features.clear()
    for f in obj.ctmap.features:
        g = own.ctmap.features.add()
        g.name, g.vertex, g.image = f.name, f.vertex, f.image
    activate(own)
    before_co = [tuple(v.co) for v in own.data.vertices]
    before_uv = [tuple(d.uv) for d in own.data.uv_layers["UVMap"].data]
    s.result = 'auto'  # the object has UVs: baked
    s.bake_size = 256
    r = bpy.ops.ctmap.map()
    baked = bpy.data.images.get("nefertiti_uv_ctmap_baked")
    check(r == {'FINISHED'} and baked is not None, f"Map (b) baked an image: {s.report}")
    check([tuple(v.co) for v in own.data.vertices] == before_co, "its vertices, their count and order unchanged")
    check([tuple(d.uv) for d in own.data.uv_layers["UVMap"].data] == before_uv, "its UVs unchanged")
    check(own.material_slots and own.material_slots[0].material.node_tree.nodes.get("Image Texture").image == baked,
          "its material shows the baked image")
    # The same bake by the CLI: the map (the new object's source) and ONTO as OBJ files.
    mapped = ctmap.map_texture(np.array(V), np.array([list(f) for f in F]),
                               [{"name": f.name, "vertex": f.vertex, "image": list(f.image)} for f in own.ctmap.features],
                               image_size=(W, H))
    ctmap.write_obj(os.path.join(OUT, "map.obj"), mapped["V"], mapped["F"], mapped["UV"], PHOTO)
    uv32 = np.array(before_uv, dtype=np.float64)  # Blender's float32 UVs, per loop (= per corner: triangles)
    with open(os.path.join(OUT, "onto.obj"), "w") as fh:
        for v in V:
            fh.write("v %.17g %.17g %.17g\n" % tuple(float(x) for x in v))
        for t in uv32:
            fh.write("vt %.17g %.17g\n" % tuple(t))
        for poly in own.data.polygons:
            fh.write("f " + " ".join(f"{own.data.loops[li].vertex_index + 1}/{li + 1}" for li in poly.loop_indices) + "\n")
    c = subprocess.run([CTMAP, "bake", os.path.join(OUT, "map.obj"), os.path.join(OUT, "onto.obj"), "-o",
                        os.path.join(OUT, "cli_baked.png"), "--size", "256", "-q"], capture_output=True, text=True)
    check(c.returncode == 0, "ctmap bake ran: " + c.stderr.strip())
    cli = bpy.data.images.load(os.path.join(OUT, "cli_baked.png"))
    a = np.empty(256 * 256 * 4, np.float32)
    b = np.empty(256 * 256 * 4, np.float32)
    baked.pixels.foreach_get(a)
    cli.pixels.foreach_get(b)
    diff = int(np.abs(np.round(a * 255) - np.round(b * 255)).max())
    check(diff <= 1, f"the baked image equals ctmap bake's (max difference {diff}/255)")

    # Must-show 2: a feature added by the operator at a selected vertex, found in the result.
    activate(obj)
    for v in obj.data.vertices:
        v.select = v.index == 150
    r = bpy.ops.ctmap.add_feature(name="cheek_added", image=(300.0, 300.0))
    check(r == {'FINISHED'} and obj.ctmap.features[-1].vertex == 150, "Add feature took the selected vertex 150")
    obj.ctmap.active = 0
    bpy.ops.ctmap.select_feature()
    check([v.index for v in obj.data.vertices if v.select] == [obj.ctmap.features[0].vertex],
          "Select feature's vertex selects the first feature's vertex only")
    s.result = 'new_object'
    r = bpy.ops.ctmap.map()
    new2 = bpy.data.objects.get("nefertiti_ctmap.001")
    ok = r == {'FINISHED'} and new2 is not None
    if ok:
        want = np.array([300.0 / W, 1 - 300.0 / H])
        got = [np.array(new2.data.uv_layers["ctmap"].data[l.index].uv) for l in new2.data.loops if l.vertex_index == 150]
        ok = bool(got) and max(float(np.abs(g - want).max()) for g in got) <= 1e-6
    check(ok, "the added feature is at its image point in the new map")

    # An invalid layout: the nose far outside the border features' polygon. The scene is unchanged,
    # the panel shows the message `ctmap validate` gives for the same features.
    # (Border: given, as the paper's rules: with Auto, ctmap would place border features round it.)
    next(f for f in obj.ctmap.features if f.name == "nose_tip").image = (400.0, 400.0)
    s.border = 'given'
    before = scene_state()
    try:
        r = bpy.ops.ctmap.map()
        raised = ""
    except RuntimeError as e:  # an operator's ERROR report is raised in background mode
        r, raised = {'CANCELLED'}, str(e)
    check(r == {'CANCELLED'} and scene_state() == before, "an invalid layout leaves the scene unchanged")
    twin = os.path.join(OUT, "invalid.json")
    bpy.ops.ctmap.export_features(filepath=twin)
    v = subprocess.run([CTMAP, "validate", MESH, twin, "--border", "given"], capture_output=True, text=True)
    message = v.stderr.strip().split(": ", 3)[-1]  # "ctmap: error: FILE: <the problem>"
    check(v.returncode == 2 and message and message in s.report and message in raised,
          f"and reports the CLI's message: panel {s.report!r}, CLI {message!r}")
    # Charts on a closed mesh: cow, the two charts `ctmap starter-features --charts 2` writes
    # (front on the photo, back on its mirror image), imported and mapped with ctmap.map_charts.
    CV, CF = read_off(data("meshes/cow.off"))
    cow = make_object("cow", CV, CF)
    activate(cow)
    charts_file = os.path.join(OUT, "cow_charts.json")
    c = subprocess.run([CTMAP, "starter-features", data("meshes/cow.off"), "--image", PHOTO, "--charts", "2",
                        "-o", charts_file], capture_output=True, text=True)
    check(c.returncode == 0, "starter-features --charts 2 wrote the cow's charts")
    r = bpy.ops.ctmap.import_features(filepath=charts_file)
    check(r == {'FINISHED'} and cow.ctmap.charts_json, "the charts file imported as charts")
    s.result = 'new_object'
    r = bpy.ops.ctmap.map()
    mapped_cow = bpy.data.objects.get("cow_ctmap")
    check(r == {'FINISHED'} and mapped_cow is not None and "valid" in s.report and "charts front, back" in s.report,
          f"Map with charts made a new object: {s.report}")
    me = mapped_cow.data
    check([m.name for m in me.materials][:2] == ["cow_ctmap_front", "cow_ctmap_back"] and
          me.materials[1].node_tree.nodes["Image Texture"].image.filepath.endswith("_mirrored.png"),
          "a material per chart, the back one with the mirror image")
    charts = __import__("json").loads(cow.ctmap.charts_json)
    uv = me.uv_layers["ctmap"].data
    worst, seen = 0.0, 0
    for ci, ch in enumerate(charts):
        W2, H2 = ch["image_size"]
        for f in ch["features"]:
            want = np.array([f["image"][0] / W2, 1 - f["image"][1] / H2])
            for poly in me.polygons:
                if poly.material_index != ci:
                    continue
                for li in poly.loop_indices:
                    if me.loops[li].vertex_index == f["vertex"]:
                        worst, seen = max(worst, float(np.abs(np.array(uv[li].uv) - want).max())), seen + 1
    check(seen > 0 and worst <= 1e-6, f"every feature of every chart at its image point in that chart ({seen} corners, "
          f"worst {worst:.2e})")

    # The same charts baked into a UV layout of the cow's own (Blender's Smart UV Project).
    activate(cow)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_all(action='SELECT')
    bpy.ops.uv.smart_project(island_margin=0.01)
    bpy.ops.object.mode_set(mode='OBJECT')
    s.result = 'bake'
    s.bake_size = 512
    r = bpy.ops.ctmap.map()
    cow_baked = bpy.data.images.get("cow_ctmap_baked")
    check(r == {'FINISHED'} and cow_baked is not None and "(exact)" in s.report, f"the charts baked into the cow's UVs: {s.report}")
    if cow_baked is not None:
        px = np.empty(512 * 512 * 4, np.float32)
        cow_baked.pixels.foreach_get(px)
        check(int((px[3::4] > 0).sum()) > 512 * 512 // 4, "the baked image covers the cow's UV islands")

    if RENDER:  # must-show 3: the object with its baked texture, rendered by Blender (Cycles, CPU)
        scene = bpy.context.scene
        for o in list(bpy.data.objects):
            o.hide_render = o is not own
        cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
        scene.collection.objects.link(cam)
        centre = (np.min(V, axis=0) + np.max(V, axis=0)) / 2
        eye = mathutils.Vector((centre[0] + 2.0, centre[1] + 0.5, centre[2] + 9.0))
        cam.location = eye
        z = (eye - mathutils.Vector(centre.tolist())).normalized()  # a camera looks down its -Z
        x = mathutils.Vector((0, 1, 0)).cross(z).normalized()      # the mesh's +y up on the picture
        cam.rotation_euler = mathutils.Matrix((x, z.cross(x), z)).transposed().to_euler()
        scene.camera = cam
        sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", 'SUN'))
        sun.rotation_euler = cam.rotation_euler
        sun.data.energy = 0.75  # (W/m²: a white diffuse surface facing it stays below white)
        scene.collection.objects.link(sun)
        scene.world = scene.world or bpy.data.worlds.new("world")
        scene.render.engine = 'CYCLES'
        scene.cycles.device = 'CPU'
        scene.cycles.samples = 32
        scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
        scene.render.resolution_x = scene.render.resolution_y = 400
        scene.render.film_transparent = True
        scene.view_settings.view_transform = 'Standard'  # the photo's own colours
        scene.render.filepath = RENDER
        bpy.ops.render.render(write_still=True)
        check(os.path.isfile(RENDER), f"rendered {RENDER}")

    if failures:
        raise SystemExit(f"{len(failures)} checks failed: " + "; ".join(failures))
    print("blender add-on test: passed")


try:
    main()
except SystemExit:
    raise
except Exception:
    traceback.print_exc()
    raise SystemExit(1)
