"""The add-on's operators (bpy.ops.ctmap.*), each undoable; scripts and tests drive them."""
import json
import threading

import bmesh
import bpy
from bpy.props import BoolProperty, FloatVectorProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from . import core


def _mesh_object(context):
    obj = context.active_object
    return obj if obj is not None and obj.type == 'MESH' else None


def _selected_vertex(obj):
    if obj.mode == 'EDIT':
        bm = bmesh.from_edit_mesh(obj.data)
        active = bm.select_history.active
        if isinstance(active, bmesh.types.BMVert):
            return active.index
        for v in bm.verts:
            if v.select:
                return v.index
        return -1
    for v in obj.data.vertices:
        if v.select:
            return v.index
    return -1


class CTMAP_OT_add_feature(bpy.types.Operator):
    """Add a feature at the selected vertex (or the 3D cursor's surface point), with its image point"""
    bl_idname = "ctmap.add_feature"
    bl_label = "Add feature"
    bl_options = {'REGISTER', 'UNDO'}

    name: StringProperty(name="Name", default="")
    image: FloatVectorProperty(name="Image point", size=2, description="in pixels of the photo (x right, y down)")
    at_cursor: BoolProperty(name="At the 3D cursor", default=False)

    def execute(self, context):
        obj = _mesh_object(context)
        if obj is None:
            self.report({'ERROR'}, "ctmap: select a mesh object")
            return {'CANCELLED'}
        names = {f.name for f in obj.ctmap.features}
        name = self.name or f"feature_{len(obj.ctmap.features) + 1}"
        if name in names:
            self.report({'ERROR'}, f"ctmap: a feature is already named '{name}'")
            return {'CANCELLED'}
        if self.at_cursor:
            point = obj.matrix_world.inverted() @ context.scene.cursor.location
            vertex = -1
        else:
            vertex = _selected_vertex(obj)
            if vertex < 0:
                self.report({'ERROR'}, "ctmap: select a vertex for the feature (or use the 3D cursor)")
                return {'CANCELLED'}
        f = obj.ctmap.features.add()
        f.name, f.image = name, self.image
        if vertex < 0:
            f.use_point, f.point = True, point
        else:
            f.vertex = vertex
        obj.ctmap.active = len(obj.ctmap.features) - 1
        return {'FINISHED'}


class CTMAP_OT_remove_feature(bpy.types.Operator):
    """Remove the active feature"""
    bl_idname = "ctmap.remove_feature"
    bl_label = "Remove feature"
    bl_options = {'REGISTER', 'UNDO'}

    index: IntProperty(name="Index", default=-1, description="the feature to remove (-1: the active one)")

    def execute(self, context):
        obj = _mesh_object(context)
        if obj is None or not obj.ctmap.features:
            return {'CANCELLED'}
        i = self.index if self.index >= 0 else obj.ctmap.active
        if i >= len(obj.ctmap.features):
            return {'CANCELLED'}
        obj.ctmap.features.remove(i)
        obj.ctmap.active = max(0, min(obj.ctmap.active, len(obj.ctmap.features) - 1))
        return {'FINISHED'}


class CTMAP_OT_select_feature(bpy.types.Operator):
    """Select the active feature's vertex on the mesh (and only it)"""
    bl_idname = "ctmap.select_feature"
    bl_label = "Select feature's vertex"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        obj = _mesh_object(context)
        if obj is None or not obj.ctmap.features:
            return {'CANCELLED'}
        f = obj.ctmap.features[min(obj.ctmap.active, len(obj.ctmap.features) - 1)]
        if f.use_point or f.vertex >= len(obj.data.vertices):
            self.report({'WARNING'}, f"ctmap: feature '{f.name}' is a surface point, not a vertex of the mesh")
            return {'CANCELLED'}
        if obj.mode == 'EDIT':
            bm = bmesh.from_edit_mesh(obj.data)
            bm.verts.ensure_lookup_table()
            for v in bm.verts:
                v.select_set(v.index == f.vertex)
            bm.select_flush_mode()
            bmesh.update_edit_mesh(obj.data)
        else:
            for v in obj.data.vertices:
                v.select = v.index == f.vertex
        return {'FINISHED'}


class CTMAP_OT_import_features(bpy.types.Operator, ImportHelper):
    """Read features.json (ctmap's format) into the active object's features"""
    bl_idname = "ctmap.import_features"
    bl_label = "Import features.json"
    bl_options = {'REGISTER', 'UNDO'}
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={'HIDDEN'})

    def execute(self, context):
        obj = _mesh_object(context)
        if obj is None:
            self.report({'ERROR'}, "ctmap: select a mesh object")
            return {'CANCELLED'}
        img = context.scene.ctmap.image
        try:
            if core.is_charts_file(self.filepath):
                charts = core.read_charts_file(self.filepath)
            else:
                charts, feats = None, core.read_features_file(self.filepath, tuple(img.size) if img else None)
        except (OSError, ValueError, RuntimeError) as e:
            self.report({'ERROR'}, f"ctmap: {e}")
            return {'CANCELLED'}
        if charts is not None:  # a closed mesh's charts: mapped with ctmap.map_charts
            obj.ctmap.charts_json = json.dumps(charts)
            obj.ctmap.features.clear()
            self.report({'INFO'}, f"ctmap: {len(charts)} charts ({', '.join(c['name'] for c in charts)}) from {self.filepath}")
            return {'FINISHED'}
        obj.ctmap.charts_json = ""
        core.set_features(obj, feats)
        self.report({'INFO'}, f"ctmap: {len(feats)} features from {self.filepath}")
        return {'FINISHED'}


class CTMAP_OT_export_features(bpy.types.Operator, ExportHelper):
    """Write the active object's features as features.json (ctmap's format)"""
    bl_idname = "ctmap.export_features"
    bl_label = "Export features.json"
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={'HIDDEN'})

    def execute(self, context):
        obj = _mesh_object(context)
        img = context.scene.ctmap.image
        if obj is None or img is None:
            self.report({'ERROR'}, "ctmap: select a mesh object and choose the photo")
            return {'CANCELLED'}
        core.write_features_file(self.filepath, core.features_of(obj), tuple(img.size), bpy.path.abspath(img.filepath))
        return {'FINISHED'}


class CTMAP_OT_map(bpy.types.Operator):
    """Map the active object so every feature lands exactly on its image point (a certified map), then make a
new textured object or bake the photo into the object's own UVs"""
    bl_idname = "ctmap.map"
    bl_label = "Map"
    bl_options = {'REGISTER', 'UNDO'}

    _thread = None
    _timer = None

    def _finish(self, context, obj, result):
        s = context.scene.ctmap
        mode = s.result
        if mode == 'auto':
            mode = 'bake' if obj.data.uv_layers.active is not None else 'new_object'
        if mode == 'bake':
            baked, b = core.bake_into(obj, result, s.image, s.bake_size)
            where = f"baked into '{obj.name}'s UVs as image '{baked.name}' ({'exact' if b['exact'] else 'closest point'})"
        else:
            new = core.make_object(context, obj, result, s.image)
            where = f"new object '{new.name}'"
        s.report = f"{core.certificate_text(result)}; {where}"
        self.report({'INFO'}, "ctmap: " + s.report)

    def execute(self, context):
        obj = _mesh_object(context)
        s = context.scene.ctmap
        try:
            result = core.run_map(obj, s)
            self._finish(context, obj, result)
        except (ValueError, ImportError) as e:
            s.report = f"error: {e}"
            self.report({'ERROR'}, f"ctmap: {e}")
            return {'CANCELLED'}
        return {'FINISHED'}

    def invoke(self, context, event):
        # From the UI: the map runs in a thread (the module releases the GIL), Blender stays
        # responsive, the status bar says so, Esc stops waiting (the map itself runs to its end).
        obj = _mesh_object(context)
        s = context.scene.ctmap
        try:
            args = core.prepare_map(obj, s)  # Blender's data read here, on its own thread
        except ValueError as e:
            s.report = f"error: {e}"
            self.report({'ERROR'}, f"ctmap: {e}")
            return {'CANCELLED'}
        self._box = {}
        self._obj_name = obj.name

        def work():
            try:
                self._box["result"] = core.compute_map(args)
            except (ValueError, ImportError, RuntimeError) as e:
                self._box["error"] = e

        self._thread = threading.Thread(target=work, daemon=True)
        self._thread.start()
        self._timer = context.window_manager.event_timer_add(0.2, window=context.window)
        context.window_manager.modal_handler_add(self)
        context.workspace.status_text_set("ctmap: mapping… (Esc to stop waiting)")
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if event.type == 'ESC':
            self._end(context)
            self.report({'WARNING'}, "ctmap: stopped waiting; the scene is unchanged")
            return {'CANCELLED'}
        if event.type != 'TIMER' or self._thread.is_alive():
            return {'PASS_THROUGH'}
        self._end(context)
        s = context.scene.ctmap
        if "error" in self._box:
            s.report = f"error: {self._box['error']}"
            self.report({'ERROR'}, f"ctmap: {self._box['error']}")
            return {'CANCELLED'}
        try:
            self._finish(context, bpy.data.objects[self._obj_name], self._box["result"])
        except (ValueError, ImportError) as e:
            s.report = f"error: {e}"
            self.report({'ERROR'}, f"ctmap: {e}")
            return {'CANCELLED'}
        return {'FINISHED'}

    def _end(self, context):
        context.window_manager.event_timer_remove(self._timer)
        context.workspace.status_text_set(None)


class CTMAP_OT_pick_image_point(bpy.types.Operator):
    """Click in the Image Editor to place the active feature's image point (Esc or right click to stop)"""
    bl_idname = "ctmap.pick_image_point"
    bl_label = "Pick image point"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return context.area is not None and context.area.type == 'IMAGE_EDITOR'

    def invoke(self, context, event):
        context.window_manager.modal_handler_add(self)
        context.workspace.status_text_set("ctmap: click the active feature's point in the photo (Esc: done)")
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        if event.type in {'ESC', 'RIGHTMOUSE'}:
            context.workspace.status_text_set(None)
            return {'FINISHED'}
        if event.type == 'LEFTMOUSE' and event.value == 'PRESS':
            obj = context.view_layer.objects.active
            img = context.scene.ctmap.image
            if obj is None or obj.type != 'MESH' or not obj.ctmap.features or img is None:
                self.report({'ERROR'}, "ctmap: choose the photo and a mesh object with a feature")
                return {'CANCELLED'}
            u, v = context.region.view2d.region_to_view(event.mouse_region_x, event.mouse_region_y)
            w, h = img.size
            f = obj.ctmap.features[obj.ctmap.active]
            f.image = (u * w, (1 - v) * h)
            context.area.tag_redraw()
            return {'RUNNING_MODAL'}
        return {'PASS_THROUGH'}


CLASSES = [CTMAP_OT_add_feature, CTMAP_OT_remove_feature, CTMAP_OT_select_feature, CTMAP_OT_import_features, CTMAP_OT_export_features,
           CTMAP_OT_map, CTMAP_OT_pick_image_point]
