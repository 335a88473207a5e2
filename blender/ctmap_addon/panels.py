"""The sidebar panels (3D View and Image Editor, tab "ctmap"), the features list, and the
features' image points drawn over the photo in the Image Editor (gpu module)."""
import textwrap

import bpy
import gpu
from gpu_extras.batch import batch_for_shader

from . import module_finder


class CTMAP_UL_features(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index):
        row = layout.row(align=True)
        row.prop(item, "name", text="", emboss=False)
        row.label(text=("point" if item.use_point else f"v {item.vertex}"))
        row.label(text=f"({item.image[0]:.0f}, {item.image[1]:.0f})")


def _draw(layout, context):
    s = context.scene.ctmap
    obj = context.active_object
    try:
        module_finder.load()
    except ImportError as e:
        box = layout.box()
        box.alert = True
        for line in str(e).split("; "):
            box.label(text=line[:120])
        return
    layout.template_ID(s, "image", open="image.open")
    if obj is None or obj.type != 'MESH':
        layout.label(text="Select a mesh object")
        return
    if obj.ctmap.charts_json:
        import json
        charts = json.loads(obj.ctmap.charts_json)
        box = layout.box()
        box.label(text=f"{obj.name}: {len(charts)} charts from a features file")
        for ch in charts:
            box.label(text=f"{ch['name']}: {len(ch['features'])} features, {len(ch['border'])} on its border")
    layout.label(text=f"Features of {obj.name}:")
    row = layout.row()
    row.template_list("CTMAP_UL_features", "", obj.ctmap, "features", obj.ctmap, "active", rows=4)
    col = row.column(align=True)
    col.operator("ctmap.add_feature", icon='ADD', text="")
    col.operator("ctmap.remove_feature", icon='REMOVE', text="")
    col.operator("ctmap.select_feature", icon='RESTRICT_SELECT_OFF', text="")
    if obj.ctmap.features:
        f = obj.ctmap.features[min(obj.ctmap.active, len(obj.ctmap.features) - 1)]
        box = layout.box()
        box.prop(f, "image")
        box.prop(f, "use_point")
        box.prop(f, "point" if f.use_point else "vertex")
    row = layout.row(align=True)
    row.operator("ctmap.import_features", text="Import", icon='IMPORT')
    row.operator("ctmap.export_features", text="Export", icon='EXPORT')
    layout.prop(s, "refine")
    layout.prop(s, "border")
    layout.prop(s, "border_mode")
    layout.prop(s, "result")
    layout.prop(s, "bake_size")
    layout.operator("ctmap.map", icon='UV')
    if s.report:
        box = layout.box()
        box.alert = s.report.startswith("error")
        # Wrapped to the sidebar's width (about 7 pixels a character), one label a line.
        width = max(20, int(context.region.width / 7)) if context.region else 40
        for line in textwrap.wrap(s.report, width):
            box.label(text=line)


class VIEW3D_PT_ctmap(bpy.types.Panel):
    bl_label = "ctmap"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "ctmap"

    def draw(self, context):
        _draw(self.layout, context)


class IMAGE_PT_ctmap(bpy.types.Panel):
    bl_label = "ctmap"
    bl_space_type = 'IMAGE_EDITOR'
    bl_region_type = 'UI'
    bl_category = "ctmap"

    def draw(self, context):
        self.layout.operator("ctmap.pick_image_point", icon='EYEDROPPER')
        _draw(self.layout, context)


CLASSES = [CTMAP_UL_features, VIEW3D_PT_ctmap, IMAGE_PT_ctmap]
_handle = None


def _draw_points():
    context = bpy.context
    obj = context.active_object
    img = context.scene.ctmap.image if hasattr(context.scene, "ctmap") else None
    space = context.space_data
    if obj is None or obj.type != 'MESH' or img is None or space is None or space.image != img:
        return
    w, h = img.size
    if not w or not h or not obj.ctmap.features:
        return
    v2d = context.region.view2d
    pts = [v2d.view_to_region(f.image[0] / w, 1 - f.image[1] / h, clip=False) for f in obj.ctmap.features]
    try:
        shader = gpu.shader.from_builtin('UNIFORM_COLOR')
    except ValueError:  # Blender before 3.4's names
        shader = gpu.shader.from_builtin('2D_UNIFORM_COLOR')
    gpu.state.point_size_set(8)
    batch = batch_for_shader(shader, 'POINTS', {"pos": pts})
    shader.uniform_float("color", (1.0, 0.8, 0.1, 1.0))
    batch.draw(shader)
    a = min(obj.ctmap.active, len(pts) - 1)
    shader.uniform_float("color", (1.0, 0.2, 0.2, 1.0))
    batch_for_shader(shader, 'POINTS', {"pos": [pts[a]]}).draw(shader)


def add_draw_handler():
    global _handle
    if _handle is None and not bpy.app.background:
        _handle = bpy.types.SpaceImageEditor.draw_handler_add(_draw_points, (), 'WINDOW', 'POST_PIXEL')


def remove_draw_handler():
    global _handle
    if _handle is not None:
        bpy.types.SpaceImageEditor.draw_handler_remove(_handle, 'WINDOW')
        _handle = None
