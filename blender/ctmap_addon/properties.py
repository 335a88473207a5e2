"""The add-on's data: per object its features (a named entry each: mesh vertex, image point in
pixels), per scene the photo and the options of `ctmap map`, and the last run's report."""
import bpy
from bpy.props import (CollectionProperty, EnumProperty, FloatVectorProperty, IntProperty, PointerProperty,
                       StringProperty)


class CtmapFeature(bpy.types.PropertyGroup):
    # `name` (the feature's name, as in features.json) comes with PropertyGroup.
    vertex: IntProperty(name="Vertex", description="the mesh vertex the feature is at (0-based)", min=0)
    use_point: bpy.props.BoolProperty(name="Surface point", default=False,
                                      description="at a point on the surface (ctmap inserts a vertex there) instead of a vertex")
    point: FloatVectorProperty(name="Point", description="the surface point, in the object's own coordinates", size=3)
    image: FloatVectorProperty(name="Image point", description="where it lands in the photo, in pixels "
                               "(x right, y down from the top-left corner, as in features.json)", size=2)


class CtmapObjectSettings(bpy.types.PropertyGroup):
    features: CollectionProperty(type=CtmapFeature)
    active: IntProperty(name="Active feature", default=0)
    # A closed mesh's charts (a features file with "charts", e.g. `ctmap starter-features --charts 2`):
    # the file's charts as JSON, image paths absolute, image points in pixels. Empty: one chart, `features`.
    charts_json: StringProperty(name="Charts", default="")


class CtmapSceneSettings(bpy.types.PropertyGroup):
    image: PointerProperty(name="Photo", type=bpy.types.Image, description="the photo the features are placed on")
    refine: EnumProperty(name="Refine", default="isometric", items=[
        ("isometric", "Isometric", "the relaxation, then the distortion optimiser (ctmap map's default)"),
        ("paper", "Paper", "the paper's relaxation only"),
        ("none", "None", "the bare mean value embedding")])
    border: EnumProperty(name="Border", default="auto", items=[
        ("auto", "Auto", "place border features where the given ones cannot make a border"),
        ("given", "Given", "the paper's rules: the border features you marked")])
    border_mode: EnumProperty(name="Border mode", default="free", items=[
        ("free", "Free", "the optimiser moves the border (inside the image)"),
        ("fixed", "Fixed", "the border stays on the feature polygon's sides")])
    result: EnumProperty(name="Result", default="auto", items=[
        ("auto", "Auto", "bake into the object's own UVs when it has some, else a new object"),
        ("new_object", "New object", "a new object with the mapped mesh, a UV map and a material with the photo"),
        ("bake", "Bake into UVs", "the photo baked into the object's own UV layout, its mesh untouched")])
    bake_size: IntProperty(name="Bake size", default=0, min=0, max=16384,
                           description="texels per side of the baked image (0: the photo's size)")
    report: StringProperty(name="Last run", default="")


CLASSES = [CtmapFeature, CtmapObjectSettings, CtmapSceneSettings]


def attach():
    bpy.types.Object.ctmap = PointerProperty(type=CtmapObjectSettings)
    bpy.types.Scene.ctmap = PointerProperty(type=CtmapSceneSettings)


def detach():
    del bpy.types.Object.ctmap
    del bpy.types.Scene.ctmap
