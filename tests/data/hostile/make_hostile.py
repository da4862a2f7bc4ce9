#!/usr/bin/env python3
"""Writes the hand-made hostile inputs of issue 11 (tests/e2e/hostile_input_test.cpp runs them).

Each file is small and exercises one way a file could crash, hang, exhaust memory, read outside
its folder or render wrong in silence. Run it from anywhere; it writes next to itself. The FIFO,
/dev/zero and the oversized sparse file are made by the test at run time instead.
"""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

# One triangle facing +z, seen by a camera at z = 3; 36 bytes of float positions.
TRIANGLE = struct.pack("<9f", -1, -1, 0, 1, -1, 0, 0, 1, 0)
TRIANGLE_URI = "data:application/octet-stream;base64," + base64.b64encode(TRIANGLE).decode()


def scene(buffer_uri=TRIANGLE_URI, material=None, camera_translation=(0, 0, 3), extra_nodes=(),
          extensions_used=(), lights=None, images=None, position_accessor=None):
    doc = {
        "asset": {"version": "2.0", "generator": "tests/data/hostile/make_hostile.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1] + [2 + i for i in range(len(extra_nodes))]}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": list(camera_translation)}] + list(extra_nodes),
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}],
        "buffers": [{"uri": buffer_uri, "byteLength": len(TRIANGLE)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(TRIANGLE)}],
        "accessors": [position_accessor or {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                                            "min": [-1, -1, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
        "materials": [material or {"emissiveFactor": [1, 1, 1]}],
    }
    if extensions_used:
        doc["extensionsUsed"] = list(extensions_used)
    if lights is not None:
        doc["extensions"] = {"KHR_lights_punctual": {"lights": lights}}
    if images is not None:
        doc["images"] = images
        doc["textures"] = [{"source": 0}]
        doc["materials"][0]["pbrMetallicRoughness"] = {"baseColorTexture": {"index": 0}}
    return doc


def write_json(name, doc):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def glb(doc_text):
    body = doc_text.encode()
    body += b" " * (-len(body) % 4)
    return struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(body)) + struct.pack("<II", len(body), 0x4E4F534A) + body


def png(width, height):
    """An all-black 8-bit greyscale PNG: deflate packs its gigabytes of claimed texels tightly."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    row = b"\0" * (width + 1)  # filter byte 0, then the row
    compressor = zlib.compressobj(9)
    idat = b"".join(compressor.compress(row) for _ in range(height)) + compressor.flush()
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
            chunk(b"IDAT", idat) + chunk(b"IEND", b""))


def exr_claim(width, height):
    """A ZIP scanline EXR claiming width x height FLOAT R, G, B pixels: a header and a line
    offset table (one zero per 16 lines, which OpenEXR accepts), but no pixel data."""
    def attribute(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    channels = b"".join(c.encode() + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (attribute("channels", "chlist", channels) + attribute("compression", "compression", b"\3") +
              attribute("dataWindow", "box2i", box) + attribute("displayWindow", "box2i", box) +
              attribute("lineOrder", "lineOrder", b"\0") + attribute("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              attribute("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    return struct.pack("<II", 20000630, 2) + header + b"\0" * (8 * ((height + 15) // 16))


def main():
    # 8. Nesting: 15,000 levels of [ in extras (about 30 KB), as JSON and inside a .glb.
    deep = json.dumps(scene(), indent=1)
    deep = deep.replace('"asset": {', '"extras": ' + "[" * 15000 + "]" * 15000 + ', "asset": {', 1)
    with open(os.path.join(HERE, "deep_nesting.gltf"), "w") as f:
        f.write(deep)
    with open(os.path.join(HERE, "deep_nesting.glb"), "wb") as f:
        f.write(glb(deep.replace("[" * 15000, "{\"a\":" * 15000 + "0", 1).replace("]" * 15000, "}" * 15000, 1)))

    # 9. URIs that leave the scene's folder, or rely on the current directory.
    write_json("uri_parent_escape.gltf", scene(buffer_uri="../" * 16 + "etc/passwd"))
    write_json("uri_absolute.gltf", scene(buffer_uri="/etc/passwd"))
    write_json("uri_image_escape.gltf", scene(images=[{"uri": "../" * 16 + "etc/passwd"}]))
    write_json("uri_cwd_fallback.gltf", scene(buffer_uri="only_in_working_directory.bin"))
    write_json("uri_fifo.gltf", scene(buffer_uri="fifo.bin"))  # the test makes fifo.bin a FIFO

    # 10. Small files claiming huge allocations.
    with open(os.path.join(HERE, "huge_claim.png"), "wb") as f:
        f.write(png(16384, 16384))
    write_json("huge_claim_png.gltf", scene(images=[{"uri": "huge_claim.png"}]))
    with open(os.path.join(HERE, "huge_claim.exr"), "wb") as f:
        f.write(exr_claim(20000, 20000))
    with open(os.path.join(HERE, "huge_claim_16k.exr"), "wb") as f:  # within the side limit, not the file's
        f.write(exr_claim(16384, 16384))
    write_json("dataless_accessor.gltf", scene(position_accessor={
        "componentType": 5126, "count": 30000000, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}))

    # 2. Finite doubles that float cannot hold.
    write_json("emissive_strength_1e39.gltf", scene(
        material={"emissiveFactor": [1, 1, 1],
                  "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1e39}}},
        extensions_used=["KHR_materials_emissive_strength"]))
    write_json("light_intensity_1e39.gltf", scene(
        material={"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}},
        extra_nodes=[{"translation": [0, 0, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        lights=[{"type": "point", "intensity": 1e39}], extensions_used=["KHR_lights_punctual"]))
    write_json("camera_translation_1e300.gltf", scene(camera_translation=(0, 0, 1e300)))
    # Every node's own scale fits; their product (1e60) carries the vertices beyond float.
    doc = scene()
    doc["nodes"][0] = {"scale": [1e30, 1e30, 1e30], "children": [2]}
    doc["nodes"].append({"scale": [1e30, 1e30, 1e30], "mesh": 0})
    write_json("nested_scale_1e60.gltf", doc)


if __name__ == "__main__":
    main()
