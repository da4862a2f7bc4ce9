"""A small glTF 2.0 reader for the speed benchmark's Mitsuba stand-in (benchmarks/speed.py): numpy
only, enough for the shipped scenes. Reads .gltf (buffers as data: URIs or files) and .glb (the
binary chunk), walks the node hierarchy (TRS or matrix) and returns, in world space:

- triangle meshes: one per primitive (mode 4), positions, normals (from the inverse transpose;
  face normals where the file has none), TEXCOORD_0 where present, indices, material index;
- materials: pbrMetallicRoughness factors and textures, emissive radiance (emissiveFactor times
  KHR_materials_emissive_strength) and emissive texture, doubleSided;
- images as raw bytes (PNG/JPEG) with their sampler;
- the first perspective camera (position, forward = the node's -Z, up = its +Y, yfov);
- KHR_lights_punctual lights (point, spot, directional) with position and direction (-Z).

What it does not read (none of the shipped scenes uses it): sparse accessors, morph targets,
skins, KHR_texture_transform, texture coordinate sets other than 0, vertex colours, normal maps,
transmission/volume/IOR (the materials are read as opaque principled ones).
"""
import base64
import json
import os
import struct

import numpy as np

_COMPONENT = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
_COUNT = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def _load(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        length = struct.unpack_from("<I", data, 8)[0]
        offset, doc, binary = 12, None, None
        while offset < length:
            chunk_len, chunk_type = struct.unpack_from("<II", data, offset)
            chunk = data[offset + 8: offset + 8 + chunk_len]
            if chunk_type == 0x4E4F534A:  # JSON
                doc = json.loads(chunk.decode("utf-8"))
            elif chunk_type == 0x004E4942:  # BIN
                binary = chunk
            offset += 8 + chunk_len
        return doc, binary
    return json.loads(data.decode("utf-8")), None


def _buffers(doc, binary, root):
    out = []
    for b in doc.get("buffers", []):
        uri = b.get("uri")
        if uri is None:
            out.append(binary)
        elif uri.startswith("data:"):
            out.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            with open(os.path.join(root, uri), "rb") as f:
                out.append(f.read())
    return out


def _view_bytes(doc, buffers, index):
    v = doc["bufferViews"][index]
    start = v.get("byteOffset", 0)
    return buffers[v["buffer"]][start: start + v["byteLength"]], v.get("byteStride")


def _accessor(doc, buffers, index):
    a = doc["accessors"][index]
    if "sparse" in a:
        raise SystemExit("speed_gltf: sparse accessors are not read")
    dtype = np.dtype(_COMPONENT[a["componentType"]])
    n, count = _COUNT[a["type"]], a["count"]
    raw, stride = _view_bytes(doc, buffers, a["bufferView"])
    offset = a.get("byteOffset", 0)
    elem = dtype.itemsize * n
    stride = stride or elem
    if stride == elem:
        arr = np.frombuffer(raw, dtype, count * n, offset).reshape(count, n)
    else:
        arr = np.stack([np.frombuffer(raw, dtype, n, offset + i * stride) for i in range(count)])
    if a.get("normalized") and dtype.kind in "iu":
        arr = arr.astype(np.float32) / np.iinfo(dtype).max
    return arr


def _quat_matrix(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def _local(node):
    if "matrix" in node:
        return np.array(node["matrix"], float).reshape(4, 4).T  # column-major in the file
    m = np.eye(4)
    m[:3, :3] = _quat_matrix(node.get("rotation", [0, 0, 0, 1])) * np.array(node.get("scale", [1, 1, 1]))
    m[:3, 3] = node.get("translation", [0, 0, 0])
    return m


def _world_nodes(doc):
    """(node index, world matrix) for every node reachable from the default scene."""
    scenes = doc.get("scenes")
    if scenes:
        roots = scenes[doc.get("scene", 0)]["nodes"]
    else:
        children = {c for n in doc.get("nodes", []) for c in n.get("children", [])}
        roots = [i for i in range(len(doc.get("nodes", []))) if i not in children]
    out, stack = [], [(r, np.eye(4)) for r in roots]
    while stack:
        i, parent = stack.pop()
        world = parent @ _local(doc["nodes"][i])
        out.append((i, world))
        stack += [(c, world) for c in doc["nodes"][i].get("children", [])]
    return out


def load(path):
    doc, binary = _load(path)
    buffers = _buffers(doc, binary, os.path.dirname(os.path.abspath(path)))
    scene = {"meshes": [], "materials": [], "images": [], "textures": [], "camera": None, "lights": []}

    for img in doc.get("images", []):
        if "bufferView" in img:
            data = _view_bytes(doc, buffers, img["bufferView"])[0]
        elif img["uri"].startswith("data:"):
            data = base64.b64decode(img["uri"].split(",", 1)[1])
        else:
            with open(os.path.join(os.path.dirname(os.path.abspath(path)), img["uri"]), "rb") as f:
                data = f.read()
        ext = ".jpg" if img.get("mimeType") == "image/jpeg" or data[:2] == b"\xff\xd8" else ".png"
        scene["images"].append({"data": bytes(data), "ext": ext})
    samplers = doc.get("samplers", [])
    for t in doc.get("textures", []):
        s = samplers[t["sampler"]] if "sampler" in t else {}
        scene["textures"].append({"image": t.get("source"), "nearest": s.get("magFilter") == 9728})

    for m in doc.get("materials", []):
        pbr = m.get("pbrMetallicRoughness", {})
        strength = m.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        scene["materials"].append({
            "name": m.get("name", ""),
            "base_color": list(pbr.get("baseColorFactor", [1, 1, 1, 1]))[:3],
            "base_color_texture": pbr.get("baseColorTexture", {}).get("index"),
            "metallic": float(pbr.get("metallicFactor", 1.0)),
            "roughness": float(pbr.get("roughnessFactor", 1.0)),
            "metallic_roughness_texture": pbr.get("metallicRoughnessTexture", {}).get("index"),
            "emission": [float(c) * strength for c in m.get("emissiveFactor", [0, 0, 0])],
            "emissive_texture": m.get("emissiveTexture", {}).get("index"),
            "double_sided": bool(m.get("doubleSided", False)),
        })

    punctual = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    cameras = doc.get("cameras", [])
    first_perspective = next((i for i, c in enumerate(cameras) if c.get("type") == "perspective"), None)
    for index, world in _world_nodes(doc):
        node = doc["nodes"][index]
        position, forward, up = world[:3, 3], -world[:3, 2], world[:3, 1]
        if "camera" in node and node["camera"] == first_perspective and scene["camera"] is None:
            scene["camera"] = {"position": position.tolist(), "forward": (forward / np.linalg.norm(forward)).tolist(),
                               "up": (up / np.linalg.norm(up)).tolist(),
                               "yfov": cameras[first_perspective]["perspective"]["yfov"]}
        light = node.get("extensions", {}).get("KHR_lights_punctual")
        if light is not None:
            l = punctual[light["light"]]
            spot = l.get("spot", {})
            scene["lights"].append({"type": l["type"], "position": position.tolist(),
                                    "direction": (forward / np.linalg.norm(forward)).tolist(),
                                    "up": (up / np.linalg.norm(up)).tolist(),
                                    "intensity": [float(c) * l.get("intensity", 1.0) for c in l.get("color", [1, 1, 1])],
                                    "inner": spot.get("innerConeAngle", 0.0),
                                    "outer": spot.get("outerConeAngle", np.pi / 4)})
        if "mesh" not in node:
            continue
        normal_matrix = np.linalg.inv(world[:3, :3]).T
        flip = np.linalg.det(world[:3, :3]) < 0
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            if prim.get("mode", 4) != 4:
                continue
            attrs = prim["attributes"]
            p = _accessor(doc, buffers, attrs["POSITION"]).astype(np.float64)
            p = p @ world[:3, :3].T + world[:3, 3]
            if "indices" in prim:
                idx = _accessor(doc, buffers, prim["indices"]).reshape(-1, 3).astype(np.uint32)
            else:
                idx = np.arange(len(p), dtype=np.uint32).reshape(-1, 3)
            if flip:
                idx = idx[:, ::-1].copy()
            if "NORMAL" in attrs:
                n = _accessor(doc, buffers, attrs["NORMAL"]).astype(np.float64) @ normal_matrix.T
                n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-20)
            else:  # flat shading: split the vertices, one face normal per triangle
                p, idx = p[idx.reshape(-1)], np.arange(idx.size, dtype=np.uint32).reshape(-1, 3)
                tri = p.reshape(-1, 3, 3)
                fn = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
                fn /= np.maximum(np.linalg.norm(fn, axis=1, keepdims=True), 1e-20)
                n = np.repeat(fn, 3, axis=0)
            uv = _accessor(doc, buffers, attrs["TEXCOORD_0"]).astype(np.float32) if "TEXCOORD_0" in attrs else None
            scene["meshes"].append({"name": f"{node.get('name', index)}_{len(scene['meshes'])}",
                                    "positions": p.astype(np.float32), "normals": n.astype(np.float32),
                                    "uvs": uv, "indices": idx, "material": prim.get("material")})
    return scene


def write_ply(path, mesh):
    """Binary little-endian PLY with positions, normals, texture coordinates (u, v as in the file:
    (0, 0) at the image's top-left, Mitsuba's convention too) and triangle faces."""
    p, n, uv, idx = mesh["positions"], mesh["normals"], mesh["uvs"], mesh["indices"]
    props = ["x", "y", "z", "nx", "ny", "nz"] + (["u", "v"] if uv is not None else [])
    cols = [p, n] + ([uv] if uv is not None else [])
    vertices = np.ascontiguousarray(np.concatenate(cols, axis=1).astype("<f4"))
    faces = np.zeros(len(idx), dtype=[("n", "u1"), ("i", "<u4", 3)])
    faces["n"], faces["i"] = 3, idx
    header = "ply\nformat binary_little_endian 1.0\n" + f"element vertex {len(vertices)}\n" + \
        "".join(f"property float {name}\n" for name in props) + \
        f"element face {len(idx)}\nproperty list uchar uint vertex_indices\nend_header\n"
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(vertices.tobytes())
        f.write(faces.tobytes())
