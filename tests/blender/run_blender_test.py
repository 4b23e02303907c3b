#!/usr/bin/env python3
"""The Blender add-on's tests (blender/glint_gltf), run by ctest (label blender):

    run_blender_test.py --blender BLENDER --glint GLINT --addon-zip ZIP --work DIR roundtrip SCENE
    run_blender_test.py --blender BLENDER --glint GLINT --addon-zip ZIP --work DIR authored
    run_blender_test.py --blender BLENDER --glint GLINT --addon-zip ZIP --work DIR import-checks
    run_blender_test.py --blender BLENDER --glint GLINT --addon-zip ZIP --work DIR --schema SCHEMA fields

roundtrip SCENE: `glint export SCENE -o a.glb`; Blender, with the add-on installed from ZIP, imports
a.glb and exports b.glb; `glint render` of b.glb matches that of a.glb within ROUNDTRIP_RELATIVE_MSE.
authored: a glinty sphere authored from scratch in Blender with the add-on (blender_session.py
author) is exported, and glint renders glints on it (pixels over twice the smooth render's); the
same .blend exported by Blender without the add-on enabled has no glint layer and no glints.
import-checks: the add-on's importer refuses a value outside the extension's range (one line naming
the file, the material and the value; the material imported without its layer), takes booleans
written as 0 and 1, and keeps a pattern seed over Blender's largest integer modulo 2^31, saying so.
fields: the add-on's Blender properties (bounds, defaults, choices) are those of the extension's
JSON schema SCHEMA, which glint writes from its one table of the layer's fields.

Each Blender session runs with its user scripts and preferences in DIR (BLENDER_USER_SCRIPTS,
BLENDER_USER_CONFIG), so that the add-on installs there and nothing of the user's is read or
written. Exit status 0: passed; 1: failed, with one line saying what; 77: Blender is missing."""

import argparse
import json
import os
import pathlib
import re
import shutil
import struct
import subprocess
import sys
import time

SESSION = pathlib.Path(__file__).resolve().parent / "blender_session.py"
SIZE = "128x128"

# Round trip: glint diff's relative MSE (mean over pixels and channels of (b - a)^2 / (a^2 + 0.01),
# linear radiance), b.glb's render against a.glb's. Measured at 128x128 (blender/README.md): 3.2e-8
# for sphere, 7.0e-9 for carpaint, 1.1e-8 or less for the other built-in scenes: the lights'
# candela and lux go to watts and back (40980 cd comes back as 40980.0001), Blender recomputes the
# tangents (MikkTSpace) and renormalises the normals, and flips v twice, which moves glints by float
# rounding. Anything the layer says, changed, moves it by 1e-3 or more (the sphere's log density 13 ->
# 27: 1.0e-3, another pattern seed: 2.4e-3), so 1e-6 is 30 times the largest measured error and a
# thousandth of the smallest change. (The absolute RMSE is not the measure: the grazing plane's
# glints, of radiance 10 and more, move it to 9e-4 where the relative error is 1e-8.)
ROUNDTRIP_RELATIVE_MSE = 1e-6

# Authored: the fraction of the sphere's pixels whose luminance is over twice the smooth render's.
# The smooth render is the same file at log density 30 (SMOOTH_OPTIONS), where the layer has
# converged to its target: against the Cook-Torrance target itself (--brdf cook-torrance), the
# sphere's rim, lit at grazing angles, is brighter with the layer even at log density 30 (27 of its
# 4128 pixels over twice), which is not sparkle. Measured at 128x128 (log density 8, uv scale 8):
# 0.021 (88 pixels); at log density 20 or 30 with another seed: 0; without the add-on: 0.
SMOOTH_OPTIONS = ("--log-density", "30")
MIN_GLINT_FRACTION = 0.005
MAX_FRACTION_WITHOUT_LAYER = 0.0


class Failure(Exception):
    pass


def run(command, env=None):
    result = subprocess.run([str(c) for c in command], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, env=env)
    if result.returncode != 0:
        raise Failure("%s exited with %d:\n%s" % (" ".join(str(c) for c in command), result.returncode,
                                                  result.stdout[-4000:]))
    return result.stdout


class Harness:
    def __init__(self, args):
        self.blender, self.glint, self.zip = args.blender, args.glint, args.addon_zip
        self.work = pathlib.Path(args.work)
        if self.work.exists():
            shutil.rmtree(self.work)
        self.work.mkdir(parents=True)
        # Debian's Blender runs the system's Python 3.11 and finds its standard library from the first
        # python3.11 on the PATH: a pyenv or virtualenv 3.11 ahead of /usr/bin would hide Debian's
        # numpy, which the glTF add-on needs. Blender's own folder first on the PATH keeps it to its
        # own (an official build's Python is bundled beside it, and is not looked up on the PATH).
        blender_folder = os.path.dirname(os.path.realpath(shutil.which(self.blender)))
        self.env = dict(os.environ, BLENDER_USER_SCRIPTS=str(self.work / "blender-scripts"),
                        BLENDER_USER_CONFIG=str(self.work / "blender-config"),
                        PATH=blender_folder + os.pathsep + os.environ.get("PATH", ""))

    def path(self, name):
        return self.work / name

    def blender_session(self, *arguments):
        start = time.monotonic()
        try:
            output = run([self.blender, "-b", "--factory-startup", "--python-exit-code", "1",
                          "--python", SESSION, "--", *arguments], env=self.env)
        except Failure as failure:
            if "No module named 'numpy'" in str(failure):
                raise Failure("Blender's Python finds no numpy, which its glTF add-on needs "
                              "(Debian: python3-numpy, which scripts/deps installs)") from None
            raise
        print("blender %s: %.1f s" % (arguments[0], time.monotonic() - start))
        return output

    def render(self, scene, output, *options):
        run([self.glint, "render", scene, "--size", SIZE, "-o", output, *options])
        return output

    def difference(self, image, reference):
        """glint diff's {"rmse": ..., "relmse": ...}."""
        output = run([self.glint, "diff", image, reference])
        values = dict(re.findall(r"^(rmse|relmse) (\S+)$", output, re.MULTILINE))
        if set(values) != {"rmse", "relmse"}:
            raise Failure("glint diff printed no rmse and relmse:\n" + output)
        return {name: float(value) for name, value in values.items()}

    def glint_pixels(self, glinty, smooth):
        output = self.blender_session("glint-pixels", glinty, smooth)
        line = next((l for l in output.splitlines() if l.startswith("{")), None)
        if line is None:
            raise Failure("blender_session.py glint-pixels printed no result:\n" + output)
        return json.loads(line)


def gltf_json(path):
    """The JSON chunk of a .glb."""
    data = pathlib.Path(path).read_bytes()
    if data[:4] != b"glTF":
        raise Failure("%s is not a .glb" % path)
    length = int.from_bytes(data[12:16], "little")
    return json.loads(data[20:20 + length])


def glint_materials(document):
    return [m.get("name") for m in document.get("materials", []) if "EXT_materials_glint" in m.get("extensions", {})]


def check(condition, message):
    print(("ok: " if condition else "FAILED: ") + message)
    if not condition:
        raise Failure(message)


# Export options per scene: the car paint takes the consistent LOD construction and the parquet the
# tree, so that every lod value goes through Blender.
ROUNDTRIP_EXPORT_OPTIONS = {"carpaint": ["--lod", "consistent"], "parquet": ["--lod", "tree"]}


def lod_values(document):
    return [m.get("extensions", {}).get("EXT_materials_glint", {}).get("lod")
            for m in document.get("materials", []) if "EXT_materials_glint" in m.get("extensions", {})]


def roundtrip(h, scene):
    original, again = h.path("a.glb"), h.path("b.glb")
    run([h.glint, "export", scene, "-o", original] + ROUNDTRIP_EXPORT_OPTIONS.get(scene, []))
    h.blender_session("roundtrip", h.zip, original, again)
    before, after = gltf_json(original), gltf_json(again)
    check(glint_materials(after) == glint_materials(before) and glint_materials(before),
          "the materials with EXT_materials_glint come back: %s" % glint_materials(after))
    check(lod_values(after) == lod_values(before), "the layers' lod comes back: %s, was %s"
          % (lod_values(after), lod_values(before)))
    check("EXT_materials_glint" in after.get("extensionsUsed", [])
          and "EXT_materials_glint" not in after.get("extensionsRequired", []),
          "Blender's file lists EXT_materials_glint as used, not required")
    check(len(after.get("cameras", [])) == len(before.get("cameras", []))
          and len(after.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", []))
          == len(before.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])),
          "the cameras and lights come back")
    error = h.difference(h.render(again, h.path("b.exr")), h.render(original, h.path("a.exr")))
    check(error["relmse"] <= ROUNDTRIP_RELATIVE_MSE,
          "glint render of Blender's %s.glb matches the original's: relative MSE %.3g <= %g (RMSE %.3g)"
          % (scene, error["relmse"], ROUNDTRIP_RELATIVE_MSE, error["rmse"]))


def authored(h):
    with_layer, blend, without_layer = h.path("authored.glb"), h.path("authored.blend"), h.path("without.glb")
    h.blender_session("author", h.zip, with_layer, blend)
    check(glint_materials(gltf_json(with_layer)) == ["glitter"],
          "the authored material 'glitter' is exported with EXT_materials_glint")
    counts = h.glint_pixels(h.render(with_layer, h.path("glinty.exr")),
                            h.render(with_layer, h.path("smooth.exr"), *SMOOTH_OPTIONS))
    fraction = counts["glint_pixels"] / max(1, counts["object_pixels"])
    check(counts["object_pixels"] > counts["pixels"] // 10, "the sphere covers %d of %d pixels"
          % (counts["object_pixels"], counts["pixels"]))
    check(fraction >= MIN_GLINT_FRACTION, "%.4f of the sphere's pixels are glints (over twice the smooth "
          "render), at least %g" % (fraction, MIN_GLINT_FRACTION))
    # The same .blend, its layer's data still in the material, exported by Blender without the add-on.
    h.blender_session("export-without-addon", blend, without_layer)
    check(not glint_materials(gltf_json(without_layer))
          and "EXT_materials_glint" not in gltf_json(without_layer).get("extensionsUsed", []),
          "without the add-on, Blender exports no EXT_materials_glint")
    counts = h.glint_pixels(h.render(without_layer, h.path("without-glinty.exr")),
                            h.render(without_layer, h.path("without-smooth.exr"), *SMOOTH_OPTIONS))
    fraction = counts["glint_pixels"] / max(1, counts["object_pixels"])
    check(fraction <= MAX_FRACTION_WITHOUT_LAYER, "without the add-on, %.4f of the sphere's pixels are glints"
          % fraction)


def with_glint_fields(source, target, changes):
    """Writes `source` (.glb) to `target` with `changes` made to every material's EXT_materials_glint."""
    data = pathlib.Path(source).read_bytes()
    length = int.from_bytes(data[12:16], "little")
    document = json.loads(data[20:20 + length])
    for material in document["materials"]:
        material["extensions"]["EXT_materials_glint"].update(changes)
    chunk = json.dumps(document).encode()
    chunk += b" " * (-len(chunk) % 4)  # chunks are 4-byte aligned, JSON padded with spaces
    rest = data[20 + length:]
    header = b"glTF" + (2).to_bytes(4, "little") + (12 + 8 + len(chunk) + len(rest)).to_bytes(4, "little")
    pathlib.Path(target).write_bytes(header + len(chunk).to_bytes(4, "little") + b"JSON" + chunk + rest)


def import_checks(h):
    original, refused, booleans = h.path("sphere.glb"), h.path("refused.glb"), h.path("booleans.glb")
    run([h.glint, "export", "sphere", "-o", original])
    with_glint_fields(original, refused, {"logDensity": 120})
    with_glint_fields(original, booleans, {"randomColors": 1, "logDensity": 9.5, "patternSeed": 3000000000})
    output = h.blender_session("import-layers", h.zip, refused)
    layers = json.loads(next(l for l in output.splitlines() if l.startswith("{")))
    warnings = [l for l in output.splitlines() if l.startswith("glint_gltf: ")]
    check(layers["red glint"]["enabled"] is False, "a material whose logDensity is 120 is imported without its layer")
    check(warnings == ["glint_gltf: refused.glb: material 'red glint': EXT_materials_glint.logDensity = 120 is "
                       "outside [0, 100]; imported without its glint layer"],
          "one line names the file, the material and the value: %s" % warnings)
    output = h.blender_session("import-layers", h.zip, booleans)
    layers = json.loads(next(l for l in output.splitlines() if l.startswith("{")))
    warnings = [l for l in output.splitlines() if l.startswith("glint_gltf: ")]
    check(layers["red glint"] == {"enabled": True, "log_density": 9.5, "random_colors": True,
                                  "pattern_seed": 3000000000 - 2**31, "uv_scale": 4.0},
          "randomColors 1 is read as true, patternSeed 3000000000 as 3000000000 - 2^31: %s" % layers["red glint"])
    check(len(warnings) == 1 and "patternSeed = 3000000000 is above 2147483647" in warnings[0],
          "one line says the seed is above Blender's largest integer: %s" % warnings)
    # At the bottom of the 32-bit floats: a subnormal uvScale within the extension's range is kept
    # (not raised to the smallest normal float), a relativeArea that no 32-bit float holds (it would
    # be 0) is refused, as glint's loader refuses it.
    tiny, underflow = h.path("tiny.glb"), h.path("underflow.glb")
    with_glint_fields(original, tiny, {"uvScale": 1e-40})
    with_glint_fields(original, underflow, {"relativeArea": 1e-46})
    output = h.blender_session("import-layers", h.zip, tiny)
    layer = json.loads(next(l for l in output.splitlines() if l.startswith("{")))["red glint"]
    check(layer["enabled"] and abs(layer["uv_scale"] - 1e-40) < 1e-44,
          "uvScale 1e-40 is kept as the 32-bit float nearest it: %s" % layer)
    output = h.blender_session("import-layers", h.zip, underflow)
    layers = json.loads(next(l for l in output.splitlines() if l.startswith("{")))
    warnings = [l for l in output.splitlines() if l.startswith("glint_gltf: ")]
    check(layers["red glint"]["enabled"] is False and
          warnings == ["glint_gltf: underflow.glb: material 'red glint': EXT_materials_glint.relativeArea = 1e-46 is "
                       "too small for a 32-bit float and would be 0, outside (0, 1]; imported without its glint layer"],
          "relativeArea 1e-46 is refused in one line: %s" % warnings)


def fields(h, schema_file):
    """The add-on's Blender properties against EXT_materials_glint's schema in the repository (which
    glint's own test holds equal to what glint writes from its table): the same properties, bounds
    (the exclusive minimum 0 as the smallest positive float, the seed's maximum as Blender's largest
    integer), defaults (alpha's is the roughness 0.5 squared) and choices."""
    properties = json.loads(pathlib.Path(schema_file).read_text())["properties"]
    output = h.blender_session("fields", h.zip)
    held = json.loads(next(l for l in output.splitlines() if l.startswith("{")))
    names = sorted(n for n in properties if n not in ("extensions", "extras"))
    check(sorted(held) == names, "the add-on's fields are the schema's properties: %s" % sorted(held))
    for name in names:
        schema, blender = properties[name], held[name]
        bounds = schema.get("items", schema)
        if "maximum" in bounds:
            low = bounds.get("exclusiveMinimum", bounds.get("minimum"))
            exclusive = "exclusiveMinimum" in bounds
            check(blender["range"] == [low, bounds["maximum"], exclusive],
                  "%s: the importer's range %s is the schema's" % (name, blender["range"]))
            float32 = lambda v: struct.unpack("<f", struct.pack("<f", v))[0]
            expected_low = 1.401298464324817e-45 if exclusive else low
            expected_high = min(bounds["maximum"], 2**31 - 1) if blender["type"] == "INT" else bounds["maximum"]
            same = (lambda a, b: a == b) if blender["type"] == "INT" else (lambda a, b: float32(a) == float32(b))
            check(same(blender["hard_min"], expected_low) and same(blender["hard_max"], expected_high),
                  "%s: Blender's bounds [%r, %r] are the schema's" % (name, blender["hard_min"], blender["hard_max"]))
        if "default" in schema:
            default = schema["default"]
            if blender["type"] == "ENUM":
                check(blender["default"] == default.upper().replace("-", "_"), "%s: default %s" % (name, blender["default"]))
            elif isinstance(default, list):
                check([float32(v) for v in blender["default"]] == [float32(v) for v in default],
                      "%s: default %s is the schema's %s" % (name, blender["default"], default))
            else:
                check(blender["default"] == default, "%s: default %r is the schema's %r" % (name, blender["default"], default))
        elif name == "alpha":
            check(blender["default"] == [0.25, 0.25], "alpha: default %s (the roughness 0.5 squared)" % blender["default"])
        if "enum" in schema:
            check(sorted(blender["choices"]) == sorted(schema["enum"]) and
                  sorted(blender["items"]) == sorted(v.upper().replace("-", "_") for v in schema["enum"]),
                  "%s: choices %s are the schema's" % (name, blender["choices"]))
    # The numbers a .blend file stores for the choices, as the add-on has always numbered them: a
    # file saved before reads its NDF and masking back unchanged.
    numbers = {"ndf": {"GGX": 0, "BECKMANN": 1}, "masking": {"SMITH": 0, "V_CAVITY": 1},
               "lod": {"PAPER": 0, "CONSISTENT": 1, "TREE": 2}}
    for name, expected in numbers.items():
        check(held[name]["numbers"] == expected, "%s: stored numbers %s" % (name, held[name]["numbers"]))
    print("fields: %d properties as the schema gives them" % len(names))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--blender", required=True)
    parser.add_argument("--glint", required=True)
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--schema", help="the extension's JSON schema (case fields)")
    parser.add_argument("case", choices=["roundtrip", "authored", "import-checks", "fields"])
    parser.add_argument("scene", nargs="?")
    args = parser.parse_args()
    if shutil.which(args.blender) is None:
        print("skipped: blender is not installed (scripts/deps installs it)")
        return 77
    h = Harness(args)
    try:
        if args.case == "roundtrip":
            if not args.scene:
                parser.error("roundtrip needs a SCENE")
            roundtrip(h, args.scene)
        elif args.case == "authored":
            authored(h)
        elif args.case == "fields":
            if not args.schema:
                parser.error("fields needs --schema")
            fields(h, args.schema)
        else:
            import_checks(h)
    except Failure as failure:
        print("run_blender_test.py: " + str(failure), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
