#!/usr/bin/env python3
"""Writes the input of GlintTexturedQuad.gltf: a 2 m metal quad facing +z whose glint layer uses all
three of the extension's textures (8 x 8 images, each read in its red channel): a roughness ramp
along u, a log-density ramp along v and a checkerboard of relative areas. `glint export` then
writes the sample from it (samples/README.md has the commands).

    make_textured_quad.py OUTPUT.gltf
"""
import base64
import json
import struct
import sys
import zlib

SIZE = 8


def png(red):
    """An 8-bit RGB PNG of SIZE x SIZE pixels whose red, green and blue are red(x, y) in [0, 255]."""
    rows = b"".join(b"\x00" + bytes(v for x in range(SIZE) for v in (red(x, y),) * 3) for y in range(SIZE))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", SIZE, SIZE, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")


def data_uri(mime, data):
    return f"data:{mime};base64,{base64.b64encode(data).decode()}"


def main():
    positions = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]
    normals = [0, 0, 1] * 4
    uvs = [0, 1, 1, 1, 1, 0, 0, 0]  # glTF's v runs down the image
    indices = [0, 1, 2, 0, 2, 3]
    buffer = struct.pack("<12f", *positions) + struct.pack("<12f", *normals) + struct.pack("<8f", *uvs)
    buffer += struct.pack("<6H", *indices)
    images = [
        png(lambda x, y: 128 + 127 * x // (SIZE - 1)),          # roughness: alpha times 0.5 to 1 along u
        png(lambda x, y: 255 * y // (SIZE - 1)),                # log density: logDensityRange along v
        png(lambda x, y: 255 if (x // 2 + y // 2) % 2 else 64),  # relative area: 1 and 0.25 in 2 x 2 squares
    ]
    document = {
        "asset": {"version": "2.0", "generator": "make_textured_quad.py"},
        "extensionsUsed": ["EXT_materials_glint"],
        "buffers": [{"byteLength": len(buffer), "uri": data_uri("application/octet-stream", buffer)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 96, "byteLength": 32, "target": 34962},
            {"buffer": 0, "byteOffset": 128, "byteLength": 12, "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
        "images": [{"name": name, "uri": data_uri("image/png", data)}
                   for name, data in zip(["roughness", "log density", "relative area"], images)],
        "textures": [{"source": i} for i in range(3)],
        "materials": [{
            "name": "textured glints",
            "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.75, 0.4, 1], "metallicFactor": 1, "roughnessFactor": 0.46},
            "extensions": {"EXT_materials_glint": {
                "alpha": [0.3, 0.15], "rho": 0.3, "uvScale": 2, "randomColors": True, "logDensityRange": [12, 20],
                "roughnessTexture": {"index": 0}, "logDensityTexture": {"index": 1}, "relativeAreaTexture": {"index": 2},
            }},
        }],
        "meshes": [{"name": "quad", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "nodes": [{"name": "quad", "mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    with open(sys.argv[1], "w", encoding="utf-8") as file:
        json.dump(document, file, indent=1)


if __name__ == "__main__":
    main()
