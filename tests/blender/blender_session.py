# Runs inside Blender (blender -b --factory-startup --python blender_session.py -- ACTION ...), driven
# by run_blender_test.py; one action a Blender session:
#   roundtrip ZIP IN.glb OUT.glb          the add-on installed from ZIP and enabled; IN imported, OUT exported
#   author ZIP OUT.glb OUT.blend          the add-on enabled; a glinty sphere authored from scratch, exported, saved
#   export-without-addon IN.blend OUT.glb  the add-on not enabled; IN opened and exported
#   import-layers ZIP IN.glb              the add-on enabled; IN imported; prints a JSON line: each
#                                         material's layer (enabled, log_density, random_colors, pattern_seed,
#                                         uv_scale)
#   glint-pixels GLINT.exr SMOOTH.exr     prints a JSON line: object pixels and glint pixels of a render
# The add-on is installed into the user scripts folder, which run_blender_test.py points at a
# temporary folder (BLENDER_USER_SCRIPTS), as are Blender's preferences (BLENDER_USER_CONFIG).
# Any failure exits with status 1 and one line.

import json
import math
import sys

import bpy

ADDON = "glint_gltf"

# The glTF exporter's options for everything glint renders: lights (KHR_lights_punctual, off by
# default in 3.4), cameras (off by default), tangents (the layer's alpha and rho live in the tangent
# frame; off by default), and extras (the extras.glint_specular of glint's materials without a layer;
# off by default). Lights keep the default "Standard" (SPEC) units: candela and lux at 683 lm/W, the
# same as glint's export, so that the import's conversion to watts and the export's back cancel.
EXPORT_OPTIONS = dict(export_format="GLB", export_lights=True, export_cameras=True, export_tangents=True,
                      export_extras=True, export_apply=True)


def fail(message):
    print("blender_session.py: " + message, file=sys.stderr)
    sys.exit(1)


def enable_addon(zip_path):
    bpy.ops.preferences.addon_install(filepath=zip_path)
    bpy.ops.preferences.addon_enable(module=ADDON)
    if ADDON not in bpy.context.preferences.addons:
        fail("the add-on %s did not enable" % ADDON)


def empty_scene():
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.lights, bpy.data.cameras):
        for item in list(collection):
            collection.remove(item)


def roundtrip(zip_path, source, target):
    enable_addon(zip_path)
    empty_scene()
    # The add-on's register() has put numpy.bool back for Blender 3.4's importer (numpy_compat.py).
    bpy.ops.import_scene.gltf(filepath=source)
    layers = [m.name for m in bpy.data.materials if m.glint_layer.enabled]
    print("blender_session.py: imported %d materials, %d with a glint layer: %s"
          % (len(bpy.data.materials), len(layers), ", ".join(layers)))
    bpy.ops.export_scene.gltf(filepath=target, **EXPORT_OPTIONS)


def author(zip_path, target, blend):
    enable_addon(zip_path)
    empty_scene()
    # A unit UV sphere, smooth, at the origin: its uv (the sphere's) carries the glints.
    bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=1.0, location=(0, 0, 0))
    sphere = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    material = bpy.data.materials.new("glitter")
    material.use_nodes = True
    principled = material.node_tree.nodes["Principled BSDF"]
    # A dark blue dielectric: its diffuse lobe leaves the glints room to stand out.
    principled.inputs["Base Color"].default_value = (0.01, 0.02, 0.1, 1.0)
    principled.inputs["Metallic"].default_value = 0.0
    principled.inputs["Roughness"].default_value = 0.5
    sphere.data.materials.append(material)
    # The Glint panel's fields, as a user would set them: a low density, so that it sparkles.
    glint = material.glint_layer
    glint.enabled = True
    glint.alpha_from_roughness = False
    glint.alpha = (0.3, 0.3)
    glint.log_density = 8.0
    glint.uv_scale = 8.0
    # A sun from over the camera's right shoulder, and a camera 4 m away looking at the sphere.
    sun_data = bpy.data.lights.new("sun", type="SUN")
    sun_data.energy = 4.0
    sun = bpy.data.objects.new("sun", sun_data)
    sun.rotation_euler = (math.radians(50), 0.0, math.radians(30))
    bpy.context.scene.collection.objects.link(sun)
    camera_data = bpy.data.cameras.new("camera")
    camera_data.lens = 50.0  # a 39.6 degree field of view across Blender's 36 mm sensor
    camera = bpy.data.objects.new("camera", camera_data)
    camera.location = (0.0, -5.0, 0.0)
    camera.rotation_euler = (math.radians(90), 0.0, 0.0)  # looks along +y at the sphere
    bpy.context.scene.collection.objects.link(camera)
    bpy.context.scene.camera = camera
    # A square frame, as glint renders it: the exporter's yfov is then the sensor's field of view.
    bpy.context.scene.render.resolution_x = bpy.context.scene.render.resolution_y = 128
    bpy.ops.export_scene.gltf(filepath=target, **EXPORT_OPTIONS)
    bpy.ops.wm.save_as_mainfile(filepath=blend)


def export_without_addon(blend, target):
    if ADDON in bpy.context.preferences.addons:
        fail("the add-on is enabled; this session checks Blender without it")
    bpy.ops.wm.open_mainfile(filepath=blend)
    bpy.ops.export_scene.gltf(filepath=target, **EXPORT_OPTIONS)


def import_layers(zip_path, source):
    enable_addon(zip_path)
    empty_scene()
    bpy.ops.import_scene.gltf(filepath=source)
    print(json.dumps({m.name: {"enabled": m.glint_layer.enabled, "log_density": m.glint_layer.log_density,
                               "random_colors": m.glint_layer.random_colors,
                               "pattern_seed": m.glint_layer.pattern_seed,
                               "uv_scale": m.glint_layer.uv_scale} for m in bpy.data.materials}))


def fields(zip_path):
    """The Blender properties of the glint layer as Blender holds them: each one's bounds, default and
    choices, keyed by the extension's name, for the test to hold against the extension's schema."""
    enable_addon(zip_path)
    from glint_gltf import layer
    rna = bpy.types.Material.bl_rna.properties["glint_layer"].fixed_type.bl_rna.properties
    result = {}
    for field in layer.FIELDS:
        prop = rna[field.name]
        entry = {"type": prop.type}
        if prop.type in ("FLOAT", "INT"):
            entry.update(hard_min=prop.hard_min, hard_max=prop.hard_max)
            entry["default"] = list(prop.default_array) if prop.array_length else prop.default
        elif prop.type == "BOOLEAN":
            entry["default"] = prop.default
        elif prop.type == "ENUM":
            entry["default"] = prop.default
            entry["items"] = [item.identifier for item in prop.enum_items]
            entry["numbers"] = {item.identifier: item.value for item in prop.enum_items}
        entry["range"] = [field.minimum, field.maximum, field.exclusive_minimum]
        entry["choices"] = [value for value, _, _ in field.choices] if field.choices else None
        result[field.json_name] = entry
    print(json.dumps(result))


def luminance(pixels):
    return 0.2126 * pixels[..., 0] + 0.7152 * pixels[..., 1] + 0.0722 * pixels[..., 2]


def load_linear(path):
    import numpy
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = numpy.empty(width * height * 4, dtype=numpy.float32)
    image.pixels.foreach_get(pixels)
    return pixels.reshape(height, width, 4)[..., :3]


def glint_pixels(glinty_path, smooth_path):
    """Object pixels: those of the smooth render that differ from its corner (the background, which
    has no environment but glint's uniform ambient). Glint pixels: object pixels whose luminance in
    the glinty render is over twice the smooth render's."""
    import numpy
    glinty, smooth = load_linear(glinty_path), load_linear(smooth_path)
    if glinty.shape != smooth.shape:
        fail("%s and %s differ in size" % (glinty_path, smooth_path))
    background = smooth[0, 0]
    objects = numpy.any(numpy.abs(smooth - background) > 1e-6, axis=-1)
    glints = objects & (luminance(glinty) > 2.0 * luminance(smooth))
    print(json.dumps({"pixels": int(objects.size), "object_pixels": int(objects.sum()),
                      "glint_pixels": int(glints.sum())}))


def main():
    arguments = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    actions = {"roundtrip": (roundtrip, 3), "author": (author, 3),
               "export-without-addon": (export_without_addon, 2), "import-layers": (import_layers, 2),
               "glint-pixels": (glint_pixels, 2), "fields": (fields, 1)}
    if not arguments or arguments[0] not in actions or len(arguments) != actions[arguments[0]][1] + 1:
        fail("usage: blender -b --factory-startup --python blender_session.py -- ACTION ARGS (see the file)")
    action, _ = actions[arguments[0]]
    try:
        action(*arguments[1:])
    except Exception as error:  # one line, not a traceback: Blender would go on and exit 0
        fail("%s: %s" % (arguments[0], error))


main()
