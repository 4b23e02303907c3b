# glint's Blender add-on: a material's glint layer (EXT_materials_glint) in a Glint panel, written by
# Blender's glTF exporter and read by its importer. See blender/README.md.

bl_info = {
    "name": "glint: EXT_materials_glint",
    "description": "A material's glint layer (procedural glints, Chermain et al. 2020) in the Material "
                   "properties, exported and imported with glTF as EXT_materials_glint",
    "author": "The glint developers",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Material > Glint; File > Import/Export > glTF 2.0",
    "category": "Import-Export",
}

import bpy

from . import layer, numpy_compat, panel
# The glTF add-on finds these two classes on an enabled add-on's module by these exact names.
from .gltf_hooks import glTF2ExportUserExtension, glTF2ImportUserExtension

_classes = (layer.GlintLayerProperties, panel.MATERIAL_PT_glint)


def register():
    numpy_compat.restore_numpy_bool()
    for cls in _classes:
        bpy.utils.register_class(cls)
    setattr(bpy.types.Material, layer.LAYER_PROPERTY, bpy.props.PointerProperty(type=layer.GlintLayerProperties))


def unregister():
    delattr(bpy.types.Material, layer.LAYER_PROPERTY)
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
