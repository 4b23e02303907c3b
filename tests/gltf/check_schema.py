#!/usr/bin/env python3
"""EXT_materials_glint's JSON schema (extensions/EXT_materials_glint/schema), checked with a JSON
Schema validator (Debian's python3-jsonschema, draft 2020-12): the schema is itself valid; it accepts
the extension in every sample asset, in the README's example and at the ends of every range; it
rejects values out of range, of the wrong type (booleans written as 0 or 1 included: the schema
describes the form writers write, glint's loader is more lenient) and unknown properties.

    check_schema.py EXTENSION_FOLDER CORE_SCHEMA_FOLDER

The core glTF schemas the extension's refers to (glTFProperty, textureInfo) are the reduced ones in
CORE_SCHEMA_FOLDER. Exit 77 (ctest: skipped) with one line when jsonschema is missing.
"""
import importlib.metadata
import json
import pathlib
import re
import sys

try:
    import jsonschema
    from jsonschema import Draft202012Validator
except ImportError:
    print("skipped: python3-jsonschema is not installed (scripts/deps installs it)")
    sys.exit(77)

NAME = "EXT_materials_glint"


def load(path):
    with open(path, encoding="utf-8") as file:
        return json.load(file)


def make_validator(schema, core):
    """A 2020-12 validator that resolves the core schemas by their $id (jsonschema 4.18 and later
    take a referencing.Registry; earlier ones, Debian 12's 4.10, a RefResolver)."""
    try:
        import referencing
        import referencing.jsonschema

        resources = [(s["$id"], referencing.Resource.from_contents(s, referencing.jsonschema.DRAFT202012))
                     for s in core]
        registry = referencing.Registry().with_resources(resources)
        return Draft202012Validator(schema, registry=registry)
    except ImportError:
        store = {s["$id"]: s for s in core}
        resolver = jsonschema.RefResolver(base_uri=schema["$id"], referrer=schema, store=store)
        return Draft202012Validator(schema, resolver=resolver)


def extensions_in(document):
    return [m["extensions"][NAME] for m in document.get("materials", []) if NAME in m.get("extensions", {})]


def main():
    extension_folder = pathlib.Path(sys.argv[1])
    core_folder = pathlib.Path(sys.argv[2])
    schema = load(extension_folder / "schema" / f"material.{NAME}.schema.json")
    Draft202012Validator.check_schema(schema)
    core = [load(path) for path in sorted(core_folder.glob("*.schema.json"))]
    for s in core:
        Draft202012Validator.check_schema(s)
    validator = make_validator(schema, core)
    failures = []

    def expect(instance, valid, what):
        errors = list(validator.iter_errors(instance))
        if bool(errors) == valid:
            reason = errors[0].message if errors else "accepted"
            failures.append(f"{what}: expected {'valid' if valid else 'invalid'}, got: {reason}")

    accepted = 0
    for sample in sorted((extension_folder / "samples").glob("*.gltf")):
        found = extensions_in(load(sample))
        if not found:
            failures.append(f"{sample.name}: no material carries {NAME}")
        for i, extension in enumerate(found):
            expect(extension, True, f"{sample.name} extension {i}")
            accepted += 1
    readme = (extension_folder / "README.md").read_text(encoding="utf-8")
    examples = [json.loads(block) for block in re.findall(r"```json\n(.*?)```", readme, re.S) if NAME in block]
    if not examples:
        failures.append("README.md: no JSON example with the extension")
    for i, example in enumerate(examples):
        for extension in extensions_in(example):
            expect(extension, True, f"README.md example {i}")
            accepted += 1

    # Within range: empty (every field has a default or is derived), and every range's ends.
    valid = {
        "empty": {},
        "lowest": {"alpha": [0.005, 0.005], "rho": -0.99, "logDensity": 0, "relativeArea": 1e-6,
                   "densityRandomization": 0, "maxAnisotropy": 1, "patternSeed": 0, "uvScale": 1.401298464324817e-45,
                   "logDensityRange": [0, 0]},
        "highest": {"alpha": [2, 2], "rho": 0.99, "logDensity": 100, "relativeArea": 1, "densityRandomization": 10,
                    "maxAnisotropy": 64, "patternSeed": 4294967295, "uvScale": 3.4028234663852886e38,
                    "logDensityRange": [100, 100]},
        "targets": {"ndf": "beckmann", "masking": "v-cavity", "multipleScattering": False, "randomColors": True},
        "textures": {"roughnessTexture": {"index": 0}, "logDensityTexture": {"index": 3, "texCoord": 0},
                     "relativeAreaTexture": {"index": 1, "extensions": {}, "extras": {"any": 1}}},
        "glTF property members": {"extensions": {}, "extras": {"tool": "kept"}},
    }
    for what, extension in valid.items():
        expect(extension, True, what)
    invalid = {
        "alpha below 0.005": {"alpha": [0.004, 0.5]},
        "alpha above 2": {"alpha": [0.5, 2.5]},
        "alpha as one number": {"alpha": 0.5},
        "alpha of three": {"alpha": [0.5, 0.5, 0.5]},
        "rho 1": {"rho": 1},
        "rho -1": {"rho": -1},
        "logDensity -1": {"logDensity": -1},
        "logDensity 101": {"logDensity": 101},
        "relativeArea 0": {"relativeArea": 0},
        "relativeArea 1.5": {"relativeArea": 1.5},
        "densityRandomization 11": {"densityRandomization": 11},
        "maxAnisotropy 0.5": {"maxAnisotropy": 0.5},
        "maxAnisotropy 65": {"maxAnisotropy": 65},
        "patternSeed -1": {"patternSeed": -1},
        "patternSeed 2^32": {"patternSeed": 4294967296},
        "patternSeed 1.5": {"patternSeed": 1.5},
        "uvScale 0": {"uvScale": 0},
        "uvScale below a float's smallest": {"uvScale": 1e-50},
        "uvScale beyond a float": {"uvScale": 1e39},
        "logDensityRange end 200": {"logDensityRange": [10, 200]},
        "logDensityRange of one": {"logDensityRange": [10]},
        "ndf gxx": {"ndf": "gxx"},
        "masking 1": {"masking": 1},
        "randomColors 1": {"randomColors": 1},
        "randomColors yes": {"randomColors": "yes"},
        "multipleScattering 0": {"multipleScattering": 0},
        "logDensity as a string": {"logDensity": "20"},
        "a texture as a bare index": {"roughnessTexture": 1},
        "a textureInfo without index": {"roughnessTexture": {"texCoord": 0}},
        "a textureInfo index -1": {"logDensityTexture": {"index": -1}},
        "extras.glint's name": {"density_randomisation": 2},
        "an unknown property": {"sparkle": True},
        "not an object": [1, 2],
    }
    for what, extension in invalid.items():
        expect(extension, False, what)

    for failure in failures:
        print(f"FAILED {failure}")
    print(f"schema: {accepted} sample and example extensions, {len(valid)} valid and {len(invalid)} invalid cases, "
          f"{len(failures)} failed (jsonschema {importlib.metadata.version('jsonschema')})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
