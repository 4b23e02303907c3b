# The glint layer of a Blender material: its typed properties and their EXT_materials_glint spelling.
# FIELDS is the add-on's table of the extension's properties, their kinds, ranges and defaults taken
# from the extension's schema (which glint writes from its own table): the Blender properties, the
# panel's order, the exporter's JSON and the importer's checks all come from it.

import json
import math
import pathlib
import struct

import bpy

EXTENSION_NAME = "EXT_materials_glint"
# The property on bpy.types.Material that holds the layer. Not "glint": Blender's glTF exporter
# writes a material's ID properties as its extras (export_extras), and extras.glint is the form
# glint read before the extension.
LAYER_PROPERTY = "glint_layer"

# Blender's integer properties are 32-bit signed; the extension's patternSeed goes to 2^32 - 1.
BLENDER_INT_MAX = 2**31 - 1


def _load_schema():
    """EXT_materials_glint's JSON schema, which glint writes from its one table of the layer's
    fields (`glint extension-schema`): package.py puts it in the zip beside this file; a checkout
    of the sources has it in extensions/EXT_materials_glint/schema."""
    here = pathlib.Path(__file__).resolve().parent
    for candidate in (here / SCHEMA_FILE,
                      here.parent.parent / "extensions" / EXTENSION_NAME / "schema" / SCHEMA_FILE):
        if candidate.is_file():
            with open(candidate, encoding="utf-8") as file:
                return json.load(file)
    raise RuntimeError("glint_gltf: %s is missing beside the add-on (package it with blender/package.py)" % SCHEMA_FILE)


SCHEMA_FILE = "material.%s.schema.json" % EXTENSION_NAME
SCHEMA_PROPERTIES = _load_schema()["properties"]


class Field:
    """One property of EXT_materials_glint and the Blender property that holds it: its kind, range,
    default and names from the extension's schema, its label and tooltip Blender's."""

    def __init__(self, name, json_name, label, description, default=None, soft_max=None, choice_labels=None):
        schema = SCHEMA_PROPERTIES[json_name]
        bounds = schema.get("items", schema)
        self.name = name                  # the Blender property, on Material.glint_layer
        self.json_name = json_name        # the extension's property
        self.kind = ("texture" if "allOf" in schema else "pair" if schema.get("type") == "array"
                     else "choice" if schema.get("type") == "string" else schema["type"])
        self.label = label
        self.description = description
        self.exclusive_minimum = "exclusiveMinimum" in bounds
        self.minimum = bounds.get("exclusiveMinimum", bounds.get("minimum"))
        self.maximum = bounds.get("maximum")
        self.default = default if default is not None else schema.get("default")
        if self.kind == "pair" and self.default is not None:
            self.default = tuple(self.default)
        self.soft_max = soft_max
        # choice: [(json value, Blender identifier, label)] in choice_labels' order, which is also the
        # number Blender stores in a .blend file for each (so it never changes for a value), and the
        # schema's names, which must be the same set.
        self.choices = None
        if self.kind == "choice":
            if sorted(choice_labels) != sorted(schema["enum"]):
                raise RuntimeError("glint_gltf: %s's choices %s are not the schema's %s"
                                   % (json_name, sorted(choice_labels), sorted(schema["enum"])))
            self.choices = [(value, value.upper().replace("-", "_"), label) for value, label in choice_labels.items()]

    def range_text(self):
        low = "(" if self.exclusive_minimum else "["
        return "%s%s, %s]" % (low, _number_text(self.minimum), _number_text(self.maximum))


# The smallest positive 32-bit float (subnormal; Blender's float properties hold subnormals):
# Blender's stand-in for the exclusive minimum 0 of relativeArea (a Blender property has inclusive
# bounds only).
FLOAT32_MIN_POSITIVE = 1.401298464324817e-45

# The Blender side of each field: its property name, label and tooltip (the panel's order). Kinds,
# ranges and defaults are the schema's, so that a layer enabled in Blender and exported with
# nothing changed reads back as glint reads an empty EXT_materials_glint object, but for alpha:
# see alpha_from_roughness.
FIELDS = [
    Field("alpha", "alpha", "Alpha",
          "Roughness of the lobe the glints converge to, along the tangent and the bitangent",
          default=(0.25, 0.25)),
    Field("rho", "rho", "Slope Correlation",
          "Correlation of the target's slopes in the tangent frame: highlights stretch along a diagonal"),
    Field("log_density", "logDensity", "Log Density",
          "Natural logarithm of the microfacets per unit area of glint uv: low values sparkle, high ones look smooth",
          soft_max=40.0),
    Field("relative_area", "relativeArea", "Relative Area",
          "Fraction of the cells that hold microfacets (sparse glitter below 1)"),
    Field("density_randomization", "densityRandomization", "Density Randomization",
          "How much the number of microfacets varies from cell to cell (0: the same in every cell)"),
    Field("max_anisotropy", "maxAnisotropy", "Max Anisotropy",
          "A pixel's footprint is widened until its axes' ratio is at most this"),
    Field("pattern_seed", "patternSeed", "Pattern Seed",
          "Another realisation of the same statistics: another glint pattern "
          "(Blender holds 0 to 2147483647 of the extension's 0 to 4294967295)"),
    Field("uv_scale", "uvScale", "UV Scale",
          "Glint uv = TEXCOORD_0 times this; raising it by k multiplies the facets per unit of surface by k squared",
          soft_max=100.0),
    Field("random_colors", "randomColors", "Random Colors",
          "Each cell's glints get a random colour (the flakes of a car paint)"),
    Field("lod", "lod", "Level of Detail",
          "How a cell's glints relate to the finer level's: the 2020 paper's own glints per cell; a coarse "
          "cell's glints shared out among its children so that fewer glints pop as the surface recedes "
          "(Consistent); or every cell below a level set by the density the mean of its four children, so "
          "that glints stay put (Tree)",
          choice_labels={"paper": "Paper", "consistent": "Consistent", "tree": "Tree"}),
    Field("ndf", "ndf", "NDF", "The distribution the glints converge to",
          choice_labels={"ggx": "GGX", "beckmann": "Beckmann"}),
    Field("masking", "masking", "Masking", "Masking-shadowing of the lobe",
          choice_labels={"smith": "Smith", "v-cavity": "V-Cavity"}),
    Field("multiple_scattering", "multipleScattering", "Multiple Scattering",
          "A smooth lobe adds back the energy single scattering loses on rough surfaces"),
    Field("roughness_texture", "roughnessTexture", "Roughness Texture",
          "Its red channel (linear) multiplies alpha"),
    Field("log_density_texture", "logDensityTexture", "Log Density Texture",
          "Its red channel (linear, 0 to 1) maps onto the log density range and replaces the log density"),
    Field("log_density_range", "logDensityRange", "Log Density Range",
          "The log densities the log density texture's 0 and 1 map to"),
    Field("relative_area_texture", "relativeAreaTexture", "Relative Area Texture",
          "Its red channel (linear) multiplies the relative area"),
]
if sorted(f.json_name for f in FIELDS) != sorted(n for n in SCHEMA_PROPERTIES if n not in ("extensions", "extras")):
    raise RuntimeError("glint_gltf: the add-on's fields are not the schema's properties")

FIELDS_BY_JSON_NAME = {field.json_name: field for field in FIELDS}


def _number_text(value):
    """The shortest text that reads back as `value` (0.99, not 0.98999999999999999), whole numbers
    without a trailing .0."""
    if not isinstance(value, float):
        return str(value)
    text = repr(value)
    return text[:-2] if text.endswith(".0") else text


def _blender_property(field):
    """The bpy.props property that holds `field`, its bounds the extension's."""
    common = {"name": field.label, "description": field.description}
    if field.kind in ("number", "pair"):
        low = FLOAT32_MIN_POSITIVE if field.exclusive_minimum else field.minimum
        bounds = {"min": low, "max": field.maximum, "soft_min": low,
                  "soft_max": field.soft_max if field.soft_max is not None else field.maximum}
        if field.kind == "pair":
            return bpy.props.FloatVectorProperty(size=2, default=field.default, precision=3, **bounds, **common)
        return bpy.props.FloatProperty(default=field.default, precision=3, **bounds, **common)
    if field.kind == "integer":
        return bpy.props.IntProperty(default=field.default, min=field.minimum,
                                     max=min(field.maximum, BLENDER_INT_MAX), **common)
    if field.kind == "boolean":
        return bpy.props.BoolProperty(default=field.default, **common)
    if field.kind == "choice":
        # Numbered: a .blend file stores the number, so each value keeps its own.
        items = [(identifier, label, "", number) for number, (_, identifier, label) in enumerate(field.choices)]
        default = next(identifier for value, identifier, _ in field.choices if value == field.default)
        return bpy.props.EnumProperty(items=items, default=default, **common)
    if field.kind == "texture":
        # Data, not colour: the importer marks the images Non-Color, as glint reads them.
        return bpy.props.PointerProperty(type=bpy.types.Image, **common)
    raise ValueError("unknown field kind " + field.kind)


class GlintLayerProperties(bpy.types.PropertyGroup):
    """Material.glint_layer: the material's EXT_materials_glint layer."""
    __annotations__ = {
        "enabled": bpy.props.BoolProperty(
            name="Glint Layer",
            description="Give the material's specular lobe a glint layer (exported as EXT_materials_glint)",
            default=False),
        # The extension's alpha defaults to the square of the material's roughnessFactor; this flag
        # leaves alpha out of the file, so that it follows the Principled BSDF's roughness.
        "alpha_from_roughness": bpy.props.BoolProperty(
            name="Alpha from Roughness",
            description="Leave alpha out of the file: the glints converge to the core material's lobe "
                        "(alpha = roughness squared)",
            default=True),
        **{field.name: _blender_property(field) for field in FIELDS},
    }


# --- Export: the Blender properties as the extension's JSON object ---------------------------------

def as_float32(value):
    """`value` rounded to the 32-bit float Blender holds it as."""
    return struct.unpack("<f", struct.pack("<f", value))[0]


def float32_text_value(value):
    """The shortest decimal that reads back as the same 32-bit float (what Blender holds), so that
    the file says 0.3 rather than 0.30000001192092896 and glint reads the float Blender had."""
    single = as_float32(value)
    for digits in range(1, 10):
        candidate = float("%.*g" % (digits, single))
        if as_float32(candidate) == single:
            return candidate
    return single


def extension_object(layer, texture_info):
    """The EXT_materials_glint object of `layer`: every property (as glint writes it), but alpha when
    it follows the roughness. texture_info(image) gives a textureInfo for an image."""
    result = {}
    for field in FIELDS:
        value = getattr(layer, field.name)
        if field.name == "alpha" and layer.alpha_from_roughness:
            continue
        if field.kind == "number":
            result[field.json_name] = float32_text_value(value)
        elif field.kind == "pair":
            result[field.json_name] = [float32_text_value(v) for v in value]
        elif field.kind == "integer":
            result[field.json_name] = int(value)
        elif field.kind == "boolean":
            result[field.json_name] = bool(value)
        elif field.kind == "choice":
            result[field.json_name] = next(v for v, identifier, _ in field.choices if identifier == value)
        elif field.kind == "texture":
            if value is not None:
                result[field.json_name] = texture_info(value)
    return result


# --- Import: the extension's JSON object checked and set on the Blender properties -----------------

class LayerError(Exception):
    """A value of the extension that the add-on refuses, said as one line."""


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _check_number(field, value, where):
    if not _is_number(value):
        raise LayerError("%s is %r, not a number" % (where, value))
    low_ok = value > field.minimum if field.exclusive_minimum else value >= field.minimum
    if not (low_ok and value <= field.maximum):
        raise LayerError("%s = %s is outside %s" % (where, _number_text(value), field.range_text()))
    # Blender holds 32-bit floats: a value no such float holds but 0 (1e-46) becomes 0, outside an
    # exclusive minimum of 0 (glint's loader refuses it too); where 0 is in range it is read.
    if field.exclusive_minimum and value != 0 and as_float32(value) == 0:
        raise LayerError("%s = %s is too small for a 32-bit float and would be 0, outside %s"
                         % (where, _number_text(value), field.range_text()))
    return float(value)


def checked_values(extension):
    """The extension object's values as the Blender properties take them, ({property name: value},
    [notes]), alpha_from_roughness included. Raises LayerError for what the extension does not
    allow (a reader refuses rather than clamps, README "Properties"). A pattern seed over Blender's
    largest integer is kept modulo 2^31, with a note. Booleans may be 0 and 1 (README: tools that
    keep data as custom properties write them so)."""
    if not isinstance(extension, dict):
        raise LayerError("%s is not an object" % EXTENSION_NAME)
    values = {"alpha_from_roughness": "alpha" not in extension}
    notes = []
    for json_name, value in extension.items():
        if json_name in ("extensions", "extras"):
            continue
        field = FIELDS_BY_JSON_NAME.get(json_name)
        if field is None:
            raise LayerError("%s has an unknown property '%s'" % (EXTENSION_NAME, json_name))
        where = "%s.%s" % (EXTENSION_NAME, json_name)
        if field.kind == "number":
            values[field.name] = _check_number(field, value, where)
        elif field.kind == "pair":
            if not (isinstance(value, list) and len(value) == 2):
                raise LayerError("%s is %r, not two numbers" % (where, value))
            values[field.name] = tuple(_check_number(field, v, where + "[%d]" % i) for i, v in enumerate(value))
        elif field.kind == "integer":
            if not (_is_number(value) and float(value).is_integer()):
                raise LayerError("%s is %r, not an integer" % (where, value))
            value = int(value)
            if not field.minimum <= value <= field.maximum:
                raise LayerError("%s = %d is outside %s" % (where, value, field.range_text()))
            if value > BLENDER_INT_MAX:
                notes.append("%s = %d is above %d, the largest integer a Blender property holds: "
                             "kept as %d, another glint pattern" % (where, value, BLENDER_INT_MAX,
                                                                    value % (BLENDER_INT_MAX + 1)))
                value %= BLENDER_INT_MAX + 1
            values[field.name] = value
        elif field.kind == "boolean":
            if value is True or value is False or (_is_number(value) and value in (0, 1)):
                values[field.name] = bool(value)
            else:
                raise LayerError("%s is %r, not true or false" % (where, value))
        elif field.kind == "choice":
            identifier = next((i for v, i, _ in field.choices if v == value), None)
            if identifier is None:
                raise LayerError("%s is %r, not one of %s" % (where, value, ", ".join(v for v, _, _ in field.choices)))
            values[field.name] = identifier
        elif field.kind == "texture":
            if not (isinstance(value, dict) and isinstance(value.get("index"), int)
                    and not isinstance(value.get("index"), bool) and value["index"] >= 0):
                raise LayerError("%s is %r, not a textureInfo with an index" % (where, value))
            values[field.name] = value["index"]  # a glTF texture index; the importer makes it an image
    return values, notes
