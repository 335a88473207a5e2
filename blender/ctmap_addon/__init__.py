# ctmap for Blender (issue 44): mark features on a mesh and a photo, run ctmap's constrained
# texture map in-process (the `ctmap` Python module), and give the object its texture: a new
# object with the certified map, or the photo baked into the object's own UV layout.
bl_info = {
    "name": "ctmap: constrained texture mapping",
    "author": "ctmap",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View > Sidebar > ctmap; Image Editor > Sidebar > ctmap",
    "description": "Features exactly on their image points, a certified fold-free map (Guo et al.), "
                   "or the photo baked into the object's own UVs",
    "doc_url": "https://example.invalid/ctmap#blender",
    "category": "UV",
}

from . import module_finder  # noqa: E402  (finds `ctmap` before the operators import it)

if "bpy" in locals():
    import importlib
    for m in (properties, operators, panels):  # noqa: F821
        importlib.reload(m)

import bpy  # noqa: E402

from . import operators, panels, properties  # noqa: E402

_classes = properties.CLASSES + operators.CLASSES + panels.CLASSES


def register():
    for c in _classes:
        bpy.utils.register_class(c)
    properties.attach()
    panels.add_draw_handler()


def unregister():
    panels.remove_draw_handler()
    properties.detach()
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)
