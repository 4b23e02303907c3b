# The Glint panel: Properties editor > Material, under the material's surface.

import bpy

from . import layer


class MATERIAL_PT_glint(bpy.types.Panel):
    bl_label = "Glint"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return context.material is not None

    def draw_header(self, context):
        self.layout.prop(getattr(context.material, layer.LAYER_PROPERTY), "enabled", text="")

    def draw(self, context):
        glint = getattr(context.material, layer.LAYER_PROPERTY)
        body = self.layout
        body.use_property_split = True
        body.use_property_decorate = False
        body.active = glint.enabled
        body.prop(glint, "alpha_from_roughness")
        for field in layer.FIELDS:
            row = body.row()
            if field.name == "alpha":
                row.active = not glint.alpha_from_roughness
            if field.name == "log_density":
                row.active = glint.log_density_texture is None  # the texture replaces it
            if field.name == "log_density_range":
                row.active = glint.log_density_texture is not None
            if field.kind == "texture":
                # An image selector beside its label, aligned with the property rows above.
                split = row.split(factor=0.4)
                label = split.row()
                label.alignment = "RIGHT"
                label.label(text=field.label)
                split.template_ID(glint, field.name, new="image.new", open="image.open")
            else:
                row.prop(glint, field.name)
