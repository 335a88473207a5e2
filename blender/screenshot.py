"""The README's screenshot of the add-on (docs/blender_ui.png): Blender with its window, under Xvfb.
    blender -b --factory-startup --python-expr "import bpy; bpy.ops.wm.save_as_mainfile(filepath='/tmp/empty.blend')"
    xvfb-run -a -s "-screen 0 1400x1250x24" blender /tmp/empty.blend --python blender/screenshot.py -- OUT.png
(Debian's xvfb; BLENDER_USER_CONFIG / BLENDER_USER_SCRIPTS pointed at a scratch folder keep your
profile out of it.) Installs build/blender/ctmap_addon.zip, maps nefertiti with the shipped
features, and shoots the window with the new object and the ctmap panel."""
import os
import sys

import bpy

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else os.path.join(ROOT, "docs", "blender_ui.png")


def data(rel):
    for d in (os.environ.get("CTMAP_DATA"), os.path.join(ROOT, "data"), os.path.join(ROOT, "..", "shared", "data"),
              os.path.join(ROOT, ".cache", "data")):
        if d and os.path.isfile(os.path.join(d, rel)):
            return os.path.join(d, rel)
    raise FileNotFoundError(rel)


def words(p):
    return open(p).read().split()
def setup():
    bpy.ops.preferences.addon_install(filepath=os.path.join(ROOT, "build", "blender", "ctmap_addon.zip"), overwrite=True)
    bpy.ops.preferences.addon_enable(module="ctmap_addon")
    for o in list(bpy.data.objects): bpy.data.objects.remove(o)
    w = words(data("meshes/nefertiti.off")); nv, nf = int(w[1]), int(w[2]); v = w[4:]
    V = [tuple(float(x) for x in v[3*i:3*i+3]) for i in range(nv)]; F = []; o = 3*nv
    for _ in range(nf):
        n = int(v[o]); F.append(tuple(int(x) for x in v[o+1:o+1+n])); o += n+1
    me = bpy.data.meshes.new("nefertiti"); me.from_pydata(V, [], F); me.update()
    ob = bpy.data.objects.new("nefertiti", me); bpy.context.scene.collection.objects.link(ob)
    bpy.context.view_layer.objects.active = ob; ob.select_set(True)
    img = bpy.data.images.load(data("images/astronaut.png"))
    bpy.context.scene.ctmap.image = img
    bpy.ops.ctmap.import_features(filepath=data("features/nefertiti_astronaut.json"))
    bpy.context.scene.ctmap.result = 'new_object'
    bpy.ops.ctmap.map()
    ob.hide_set(True)
    new = bpy.data.objects["nefertiti_ctmap"]
    bpy.context.view_layer.objects.active = new
    for o in bpy.data.objects: o.select_set(o is new)
    new.ctmap.features.clear()
    for f in ob.ctmap.features:
        g = new.ctmap.features.add(); g.name, g.vertex, g.image = f.name, f.vertex, f.image
    for area in bpy.context.screen.areas:
        if area.type == 'VIEW_3D':
            sp = area.spaces.active
            sp.shading.type = 'MATERIAL'
            sp.show_region_ui = True
            sp.overlay.show_floor = False
            sp.overlay.show_axis_x = sp.overlay.show_axis_y = False
            r3 = sp.region_3d
            r3.view_perspective = 'PERSP'
            for region in area.regions:
                if region.type == 'UI':
                    pass
            with bpy.context.temp_override(area=area, region=[r for r in area.regions if r.type == 'WINDOW'][0]):
                bpy.ops.view3d.view_axis(type='TOP')
                bpy.ops.view3d.view_selected()
            # the sidebar's ctmap tab
    # Blender 3.4 has no call that opens a sidebar tab: the panel is shown in the tab open by default.
    import ctmap_addon.panels as P
    bpy.utils.unregister_class(P.VIEW3D_PT_ctmap)
    P.VIEW3D_PT_ctmap.bl_category = "Item"
    bpy.utils.register_class(P.VIEW3D_PT_ctmap)
    bpy.app.timers.register(shoot, first_interval=8.0)
def shoot():
    bpy.ops.screen.screenshot(filepath=OUT)
    bpy.ops.wm.quit_blender()
setup()
