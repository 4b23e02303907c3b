# The glTF add-on's user extension hooks (io_scene_gltf2: an enabled add-on's module attributes
# glTF2ExportUserExtension and glTF2ImportUserExtension, one instance a file). The hook names and
# arguments are those of Blender 3.4's io_scene_gltf2 (3.4.50), unchanged in the glTF add-on since:
#   export: gather_material_hook(gltf2_material, blender_material, export_settings)
#   import: gather_import_material_after_hook(gltf_material, vertex_color, blender_material, gltf)

import os
import sys

import bpy

from . import layer

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
JPEG_SIGNATURE = b"\xff\xd8\xff"


def _warn(message):
    print("glint_gltf: " + message, file=sys.stderr)


def _image_bytes(image):
    """The image as PNG or JPEG bytes and their MIME type: the packed or saved file as it is (an
    image imported from glTF keeps its file's bytes, so that the texture round-trips exactly),
    otherwise the pixels written as PNG."""
    data = None
    if image.packed_file is not None:
        data = bytes(image.packed_file.data)
    elif image.source == "FILE" and image.filepath:
        path = bpy.path.abspath(image.filepath)
        if os.path.isfile(path):
            with open(path, "rb") as f:
                data = f.read()
    if data is not None and data.startswith(PNG_SIGNATURE):
        return data, "image/png"
    if data is not None and data.startswith(JPEG_SIGNATURE):
        return data, "image/jpeg"
    # Generated, or another format: the pixels as a byte PNG, through a copy saved to a temporary file.
    import tempfile
    width, height = image.size
    copy = bpy.data.images.new(image.name + " (glint export)", width, height, alpha=True)
    try:
        copy.colorspace_settings.name = "Non-Color"
        copy.pixels.foreach_set(_pixels(image))
        with tempfile.TemporaryDirectory() as folder:
            copy.filepath_raw = os.path.join(folder, "texture.png")
            copy.file_format = "PNG"
            copy.save()
            with open(copy.filepath_raw, "rb") as f:
                return f.read(), "image/png"
    finally:
        bpy.data.images.remove(copy)


def _pixels(image):
    import array
    values = array.array("f", [0.0]) * (len(image.pixels))
    image.pixels.foreach_get(values)
    return values


def _keep_layer_out_of_extras():
    """With export_extras, the glTF exporter writes a material's ID properties, the layer's among
    them, as its extras, and in 3.4 deep-copies them before the material hook runs: an image in the
    layer (a texture field) then fails the export ("cannot pickle 'Image' object"). The exporter
    skips the names in its BLACK_LIST (io_scene_gltf2/blender/com/gltf2_blender_extras.py in 3.4):
    the layer's name is put there. Where that module is not found (another glTF add-on version),
    gather_material_hook takes the layer out of the extras instead."""
    try:
        from io_scene_gltf2.blender.com import gltf2_blender_extras
    except ImportError:
        return
    skipped = getattr(gltf2_blender_extras, "BLACK_LIST", None)
    if isinstance(skipped, list) and layer.LAYER_PROPERTY not in skipped:
        skipped.append(layer.LAYER_PROPERTY)


class glTF2ExportUserExtension:
    """Writes EXT_materials_glint on every material whose glint layer is enabled."""

    def __init__(self):
        # The glTF add-on's modules, imported when an export starts (they may not be loaded when
        # this add-on registers).
        from io_scene_gltf2.io.com import gltf2_io
        from io_scene_gltf2.io.com.gltf2_io_extensions import Extension
        from io_scene_gltf2.io.exp import gltf2_io_binary_data, gltf2_io_image_data
        self.gltf2_io = gltf2_io
        self.Extension = Extension
        self.BinaryData = gltf2_io_binary_data.BinaryData
        self.ImageData = gltf2_io_image_data.ImageData
        self.textures = {}  # Blender image name -> glTF texture, one for each image in the file
        _keep_layer_out_of_extras()

    def gather_material_hook(self, gltf2_material, blender_material, export_settings):
        glint = getattr(blender_material, layer.LAYER_PROPERTY, None)
        if glint is None:
            return
        # Where _keep_layer_out_of_extras could not, the layer's ID properties are in the extras
        # (export_extras): the extension says them.
        if isinstance(gltf2_material.extras, dict) and layer.LAYER_PROPERTY in gltf2_material.extras:
            del gltf2_material.extras[layer.LAYER_PROPERTY]
            if not gltf2_material.extras:
                gltf2_material.extras = None
        if not glint.enabled:
            return
        if gltf2_material.extensions and "KHR_materials_unlit" in gltf2_material.extensions:
            _warn("material '%s' is unlit: its glint layer is not exported" % blender_material.name)
            return
        extension = layer.extension_object(glint, lambda image: self._texture_info(image, export_settings))
        if gltf2_material.extensions is None:
            gltf2_material.extensions = {}
        # Used, not required: a viewer without it draws the core material, the layer's average.
        gltf2_material.extensions[layer.EXTENSION_NAME] = self.Extension(
            name=layer.EXTENSION_NAME, extension=extension, required=False)

    def _texture_info(self, image, export_settings):
        texture = self.textures.get(image.name)
        if texture is None:
            data, mime_type = _image_bytes(image)
            name = os.path.splitext(image.name)[0]
            if export_settings["gltf_format"] == "GLTF_SEPARATE":
                # Written beside the .gltf by the exporter, as its own images are.
                source = self.gltf2_io.Image(buffer_view=None, extensions=None, extras=None, mime_type=mime_type,
                                             name=name, uri=self.ImageData(data, mime_type, name))
            else:
                source = self.gltf2_io.Image(buffer_view=self.BinaryData(data), extensions=None, extras=None,
                                             mime_type=mime_type, name=name, uri=None)
            texture = self.gltf2_io.Texture(extensions=None, extras=None, name=None, sampler=None, source=source)
            self.textures[image.name] = texture
        # glint samples its textures at TEXCOORD_0 (README "Properties"): no texCoord.
        return self.gltf2_io.TextureInfo(extensions=None, extras=None, index=texture, tex_coord=None)


class glTF2ImportUserExtension:
    """Reads EXT_materials_glint into the material's glint layer (Material.glint_layer)."""

    def gather_import_material_after_hook(self, gltf_material, vertex_color, blender_material, gltf):
        extension = (gltf_material.extensions or {}).get(layer.EXTENSION_NAME)
        if extension is None:
            return
        where = "%s: material '%s'" % (os.path.basename(gltf.filename), gltf_material.name or blender_material.name)
        try:
            values, notes = layer.checked_values(extension)
        except layer.LayerError as error:
            _warn("%s: %s; imported without its glint layer" % (where, error))
            return
        for note in notes:
            _warn("%s: %s" % (where, note))
        glint = getattr(blender_material, layer.LAYER_PROPERTY)
        for name, value in values.items():
            field = next((f for f in layer.FIELDS if f.name == name), None)
            if field is not None and field.kind == "texture":
                value = _imported_image(gltf, value, where + ": " + field.json_name)
            setattr(glint, name, value)
        glint.enabled = True


def _imported_image(gltf, texture_index, where):
    """The Blender image of glTF texture `texture_index`, made by the glTF importer's own image code
    (shared with the core material's textures); None, with a warning, if there is none."""
    textures = gltf.data.textures or []
    if texture_index >= len(textures) or textures[texture_index].source is None:
        _warn("%s: texture %d does not exist or has no image; left out" % (where, texture_index))
        return None
    source = textures[texture_index].source
    made_here = gltf.data.images[source].blender_image_name is None
    try:
        from io_scene_gltf2.blender.imp.gltf2_blender_image import BlenderImage
        BlenderImage.create(gltf, source)
    except ImportError:
        _warn("%s: this glTF add-on has no BlenderImage.create (written for Blender 3.4); texture left out" % where)
        return None
    name = gltf.data.images[source].blender_image_name
    image = bpy.data.images.get(name) if name else None
    if image is None:
        _warn("%s: image %d could not be read; left out" % (where, source))
        return None
    if made_here:
        # Data: its red channel is read as stored. An image the core material uses too keeps the
        # colour space the importer gave it.
        image.colorspace_settings.name = "Non-Color"
    return image
