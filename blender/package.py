#!/usr/bin/env python3
"""Packages the Blender add-on (blender/glint_gltf) as a zip that Blender installs
(Edit > Preferences > Add-ons > Install..., or bpy.ops.preferences.addon_install).

    python3 blender/package.py -o glint_gltf.zip

The zip holds the folder glint_gltf/ with its .py files and EXT_materials_glint's JSON schema (from
extensions/EXT_materials_glint/schema, which glint writes from its table of the layer's fields: the
add-on takes its fields' kinds, ranges and defaults from it); the same sources give the same bytes
(fixed timestamps, sorted names)."""

import argparse
import pathlib
import sys
import zipfile

ADDON = pathlib.Path(__file__).resolve().parent / "glint_gltf"
SCHEMA = (pathlib.Path(__file__).resolve().parent.parent / "extensions" / "EXT_materials_glint" / "schema"
          / "material.EXT_materials_glint.schema.json")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", required=True, help="the zip to write")
    output = pathlib.Path(parser.parse_args().output)
    sources = sorted(ADDON.glob("*.py"))
    if not sources:
        sys.exit("package.py: %s holds no .py files" % ADDON)
    if not SCHEMA.is_file():
        sys.exit("package.py: %s is missing" % SCHEMA)
    sources.append(SCHEMA)
    output.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(output, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for source in sources:
            entry = zipfile.ZipInfo("glint_gltf/" + source.name, date_time=(2020, 1, 1, 0, 0, 0))
            entry.compress_type = zipfile.ZIP_DEFLATED
            entry.external_attr = 0o644 << 16
            archive.writestr(entry, source.read_bytes())
    print("package.py: wrote %s (%d files)" % (output, len(sources)))


if __name__ == "__main__":
    main()
