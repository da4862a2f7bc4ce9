#!/usr/bin/env python3
"""Generates the glTF 2.0 scenes mixtrace ships, and checks them.

    python3 scenes/make_scenes.py            # (re)write every scene next to this script
    python3 scenes/make_scenes.py --check    # regenerate in memory, compare with the files on
                                             # disk, then parse the files back and validate them

Standard library only, and deterministic: the same bytes on every run (no time stamps, no
randomness, no dict ordering that depends on hashing).

Conventions (glTF 2.0): right-handed, +Y up, metres; a triangle's front face is counter-clockwise
seen from the front; a camera (or punctual light) node looks down its local -Z. All geometry is
written in world space (mesh nodes carry no transform), so what the file says is what gets
rendered; only camera and light nodes carry a translation and rotation.
"""
import base64
import json
import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

# ---------------------------------------------------------------------------------------------
# Small vector helpers (tuples of floats).


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return (a[0] / n, a[1] / n, a[2] / n)


def neg(a):
    return (-a[0], -a[1], -a[2])


# ---------------------------------------------------------------------------------------------
# Geometry. A Mesh is one glTF primitive: positions, normals, optional UVs, triangle indices.


class Mesh:
    def __init__(self, with_uv=False):
        self.pos = []
        self.nrm = []
        self.uv = [] if with_uv else None
        self.idx = []

    def extend(self, other):
        base = len(self.pos)
        self.pos += other.pos
        self.nrm += other.nrm
        if self.uv is not None:
            # A part without UVs gets (0,0): only meshes that want UVs ask for them.
            self.uv += other.uv if other.uv is not None else [(0.0, 0.0)] * len(other.pos)
        self.idx += [i + base for i in other.idx]
        return self

    def triangle_count(self):
        return len(self.idx) // 3


def merged(*meshes, with_uv=False):
    out = Mesh(with_uv)
    for m in meshes:
        out.extend(m)
    return out


def quad(corner, e1, e2, facing, uv_repeat=None):
    """Parallelogram corner, corner+e1, corner+e1+e2, corner+e2 whose front face looks along
    `facing`. The winding is chosen from `facing` rather than from the edge order, so a caller
    states where the light goes / where the room is, and the right winding follows."""
    n = normalize(cross(e1, e2))
    f = normalize(facing)
    if abs(dot(n, f)) < 0.999:
        raise ValueError("quad: facing %r is not perpendicular to the quad" % (facing,))
    su, sv = uv_repeat if uv_repeat else (1.0, 1.0)
    corners = [corner, add(corner, e1), add(add(corner, e1), e2), add(corner, e2)]
    uvs = [(0.0, sv), (su, sv), (su, 0.0), (0.0, 0.0)]  # image row 0 is at the e2 end
    if dot(n, f) < 0:  # reverse the loop so that it turns counter-clockwise around `facing`
        corners.reverse()
        uvs.reverse()
        n = neg(n)
    m = Mesh(with_uv=uv_repeat is not None)
    m.pos = corners
    m.nrm = [n] * 4
    if m.uv is not None:
        m.uv = uvs
    m.idx = [0, 1, 2, 0, 2, 3]
    return m


def rect(center, normal, tangent, width, height, uv_repeat=None):
    """Axis-aligned-ish rectangle centred at `center`, facing `normal`; `tangent` gives the
    direction of the `width` edge."""
    n = normalize(normal)
    u = normalize(sub(tangent, mul(n, dot(tangent, n))))
    v = cross(n, u)
    e1, e2 = mul(u, width), mul(v, height)
    corner = sub(sub(center, mul(e1, 0.5)), mul(e2, 0.5))
    return quad(corner, e1, e2, n, uv_repeat)


def oriented_box(center, axes, size, skip=(), inward=False, with_uv=False):
    """Box with edges size[k] along the unit vectors axes[k]. Faces named '+x', '-y', ... (in the
    box's own frame) listed in `skip` are left out: faces resting on a floor or against a
    ceiling are never seen and would only be coplanar with it."""
    m = Mesh(with_uv)
    for k in range(3):
        for s in (1.0, -1.0):
            name = ("+" if s > 0 else "-") + "xyz"[k]
            if name in skip:
                continue
            a = axes[k]
            o1, o2 = (k + 1) % 3, (k + 2) % 3
            fc = add(center, mul(a, s * size[k] * 0.5))
            e1 = mul(axes[o1], size[o1])
            e2 = mul(axes[o2], size[o2])
            corner = sub(sub(fc, mul(e1, 0.5)), mul(e2, 0.5))
            facing = mul(a, -s if inward else s)
            m.extend(quad(corner, e1, e2, facing, (1.0, 1.0) if with_uv else None))
    return m


def yaw_axes(yaw):
    """Box axes rotated by `yaw` radians about +Y (counter-clockwise seen from above)."""
    c, s = math.cos(yaw), math.sin(yaw)
    return [(c, 0.0, -s), (0.0, 1.0, 0.0), (s, 0.0, c)]


def box(center, size, yaw=0.0, skip=(), inward=False, with_uv=False):
    return oriented_box(center, yaw_axes(yaw), size, skip, inward, with_uv)


def box_on_floor(x, z, size, yaw=0.0, floor_y=0.0):
    """Furniture: a box standing on the floor, without its never-seen bottom face."""
    return box((x, floor_y + size[1] * 0.5, z), size, yaw, skip=("-y",))


def box_between(lo, hi, skip=()):
    """Axis-aligned box from corner `lo` to corner `hi`."""
    c = mul(add(lo, hi), 0.5)
    return box(c, sub(hi, lo), 0.0, skip)


def orient_outward(m, center):
    """Makes every triangle of a closed convex surface turn counter-clockwise seen from outside."""
    for t in range(0, len(m.idx), 3):
        a, b, c = (m.pos[m.idx[t + j]] for j in range(3))
        n = cross(sub(b, a), sub(c, a))
        centroid = mul(add(add(a, b), c), 1.0 / 3.0)
        if dot(n, sub(centroid, center)) < 0:
            m.idx[t + 1], m.idx[t + 2] = m.idx[t + 2], m.idx[t + 1]


def icosphere(center, radius, subdivisions):
    """Icosahedron refined `subdivisions` times (each splits a triangle in four), projected on
    the sphere; smooth normals. Subdivision 2 gives 162 vertices and 320 triangles."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [normalize(v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        midpoint = {}

        def mid(i, j):
            key = (min(i, j), max(i, j))
            if key not in midpoint:
                midpoint[key] = len(verts)
                verts.append(normalize(mul(add(verts[i], verts[j]), 0.5)))
            return midpoint[key]

        refined = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            refined += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = refined
    m = Mesh()
    m.pos = [add(center, mul(v, radius)) for v in verts]
    m.nrm = list(verts)
    m.idx = [i for f in faces for i in f]
    orient_outward(m, center)
    return m


def uv_sphere(center, radius, rings, segments):
    """Latitude/longitude sphere with TEXCOORD_0 (u around, v from the north pole down); the
    seam column is duplicated so u runs 0..1 without wrapping; no degenerate pole triangles."""
    m = Mesh(with_uv=True)
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2.0 * math.pi * j / segments
            n = (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))
            if i == 0 or i == rings:
                n = (0.0, 1.0 if i == 0 else -1.0, 0.0)
            m.pos.append(add(center, mul(n, radius)))
            m.nrm.append(n)
            m.uv.append((j / segments, i / rings))
    row = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b = i * row + j, i * row + j + 1
            c, d = (i + 1) * row + j, (i + 1) * row + j + 1
            if i != 0:
                m.idx += [a, c, b]
            if i != rings - 1:
                m.idx += [b, c, d]
    orient_outward(m, center)
    return m


# ---------------------------------------------------------------------------------------------
# PNG (8-bit RGB, no interlace, filter type 0 on every row).


def png_bytes(width, height, pixel):
    """`pixel(x, y)` returns an (r, g, b) tuple of ints 0..255; y = 0 is the top row."""
    raw = bytearray()
    for y in range(height):
        raw.append(0)
        for x in range(width):
            raw += bytes(pixel(x, y))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)
            + chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + chunk(b"IEND", b""))


# ---------------------------------------------------------------------------------------------
# glTF writer.

FLOAT, UINT16, UINT32 = 5126, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
REPEAT, LINEAR, NEAREST, LINEAR_MIPMAP_LINEAR = 10497, 9729, 9728, 9987


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def f32_json(x):
    """Shortest decimal that reads back as the same float32: accessor min/max then match the
    stored data exactly without printing 17 digits."""
    v = f32(x)
    for digits in range(1, 10):
        s = "%.*g" % (digits, v)
        if f32(float(s)) == v:
            return clean(float(s))
    return clean(v)


def clean(x):
    return 0.0 if x == 0 else x  # no "-0.0" in the files


def r6(x):
    return clean(round(x, 6))


def look_rotation(forward, up=(0.0, 1.0, 0.0)):
    """Unit quaternion [x, y, z, w] turning the node's -Z onto `forward`, +Y towards `up`."""
    f = normalize(forward)
    right = normalize(cross(f, up))
    u = cross(right, f)
    back = neg(f)
    # Rotation matrix with columns right, u, back; m[row][col].
    m = [[right[0], u[0], back[0]], [right[1], u[1], back[1]], [right[2], u[2], back[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2.0
        q = ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s)
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2.0
        q = (0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s)
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2.0
        q = ((m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s)
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2.0
        q = ((m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s)
    n = math.sqrt(sum(c * c for c in q))
    return [r6(c / n) for c in q]


class GltfBuilder:
    def __init__(self, scene_name):
        self.name = scene_name
        self.bin = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "mixtrace scenes/make_scenes.py"},
            "scene": 0,
            "scenes": [{"name": scene_name, "nodes": []}],
            "nodes": [], "meshes": [], "materials": [], "accessors": [], "bufferViews": [],
            "buffers": [],
        }
        self.extensions_used = []
        self.punctual = []

    # -- binary data ------------------------------------------------------------------------
    def _view(self, data, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        self.bin += data
        self.doc["bufferViews"].append(view)
        return len(self.doc["bufferViews"]) - 1

    def _vec_accessor(self, values, type_name):
        width = len(values[0])
        flat = [f32(c) for v in values for c in v]
        view = self._view(struct.pack("<%df" % len(flat), *flat), ARRAY_BUFFER)
        acc = {"bufferView": view, "componentType": FLOAT, "count": len(values), "type": type_name,
               "min": [f32_json(min(flat[k::width])) for k in range(width)],
               "max": [f32_json(max(flat[k::width])) for k in range(width)]}
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def _index_accessor(self, indices, vertex_count):
        if vertex_count <= 65535:
            ctype, data = UINT16, struct.pack("<%dH" % len(indices), *indices)
        else:
            ctype, data = UINT32, struct.pack("<%dI" % len(indices), *indices)
        view = self._view(data, ELEMENT_ARRAY_BUFFER)
        self.doc["accessors"].append({"bufferView": view, "componentType": ctype,
                                      "count": len(indices), "type": "SCALAR",
                                      "min": [min(indices)], "max": [max(indices)]})
        return len(self.doc["accessors"]) - 1

    def _use(self, extension):
        if extension not in self.extensions_used:
            self.extensions_used.append(extension)

    # -- content ----------------------------------------------------------------------------
    def image(self, name, png):
        view = self._view(png)
        self.doc.setdefault("images", []).append(
            {"name": name, "bufferView": view, "mimeType": "image/png"})
        return len(self.doc["images"]) - 1

    def sampler(self, mag, min_filter, wrap_s=REPEAT, wrap_t=REPEAT):
        self.doc.setdefault("samplers", []).append(
            {"magFilter": mag, "minFilter": min_filter, "wrapS": wrap_s, "wrapT": wrap_t})
        return len(self.doc["samplers"]) - 1

    def texture(self, image, sampler):
        self.doc.setdefault("textures", []).append({"sampler": sampler, "source": image})
        return len(self.doc["textures"]) - 1

    def material(self, name, base=(0.8, 0.8, 0.8), metallic=0.0, roughness=1.0, emission=None,
                 base_tex=None, mr_tex=None, emissive_tex=None, double_sided=False):
        """`emission` is linear radiance (r, g, b); values above 1 go through
        KHR_materials_emissive_strength with the colour normalised to a maximum of 1."""
        pbr = {"baseColorFactor": [r6(c) for c in base] + [1.0],
               "metallicFactor": r6(metallic), "roughnessFactor": r6(roughness)}
        if base_tex is not None:
            pbr["baseColorTexture"] = {"index": base_tex}
        if mr_tex is not None:
            pbr["metallicRoughnessTexture"] = {"index": mr_tex}
        mat = {"name": name, "pbrMetallicRoughness": pbr}
        if emission is not None:
            peak = max(emission)
            if peak > 1.0:
                mat["emissiveFactor"] = [r6(c / peak) for c in emission]
                mat["extensions"] = {"KHR_materials_emissive_strength":
                                     {"emissiveStrength": r6(peak)}}
                self._use("KHR_materials_emissive_strength")
            else:
                mat["emissiveFactor"] = [r6(c) for c in emission]
        if emissive_tex is not None:
            mat["emissiveTexture"] = {"index": emissive_tex}
        if double_sided:
            mat["doubleSided"] = True
        self.doc["materials"].append(mat)
        return len(self.doc["materials"]) - 1

    def mesh(self, name, mesh, material):
        attrs = {"POSITION": self._vec_accessor(mesh.pos, "VEC3"),
                 "NORMAL": self._vec_accessor(mesh.nrm, "VEC3")}
        if mesh.uv is not None:
            attrs["TEXCOORD_0"] = self._vec_accessor(mesh.uv, "VEC2")
        prim = {"attributes": attrs, "indices": self._index_accessor(mesh.idx, len(mesh.pos)),
                "material": material, "mode": 4}
        self.doc["meshes"].append({"name": name, "primitives": [prim]})
        self._node({"name": name, "mesh": len(self.doc["meshes"]) - 1})

    def _node(self, node):
        self.doc["nodes"].append(node)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def camera(self, eye, target, yfov):
        self.doc["cameras"] = [{"name": "camera", "type": "perspective",
                                "perspective": {"yfov": r6(yfov), "znear": 0.01, "zfar": 1000.0}}]
        self._node({"name": "camera", "camera": 0, "translation": [r6(c) for c in eye],
                    "rotation": look_rotation(sub(target, eye))})

    def punctual_light(self, name, kind, color, intensity, position=None, direction=None,
                       inner=None, outer=None):
        """KHR_lights_punctual: intensity in candela (point, spot) or lux (directional)."""
        self._use("KHR_lights_punctual")
        light = {"name": name, "type": kind, "color": [r6(c) for c in color],
                 "intensity": r6(intensity)}
        if kind == "spot":
            light["spot"] = {"innerConeAngle": r6(inner), "outerConeAngle": r6(outer)}
        self.punctual.append(light)
        node = {"name": name, "extensions": {"KHR_lights_punctual": {"light": len(self.punctual) - 1}}}
        if position is not None:
            node["translation"] = [r6(c) for c in position]
        if direction is not None:
            node["rotation"] = look_rotation(direction, (0.0, 1.0, 0.0) if abs(
                normalize(direction)[1]) < 0.99 else (0.0, 0.0, -1.0))
        self._node(node)

    # -- output -----------------------------------------------------------------------------
    def _finish(self):
        doc = dict(self.doc)
        if self.punctual:
            doc["extensions"] = {"KHR_lights_punctual": {"lights": self.punctual}}
        if self.extensions_used:
            doc["extensionsUsed"] = list(self.extensions_used)
        while len(self.bin) % 4:
            self.bin.append(0)
        return doc

    def gltf(self):
        doc = self._finish()
        uri = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()
        doc["buffers"] = [{"byteLength": len(self.bin), "uri": uri}]
        return (json.dumps(doc, indent=1) + "\n").encode()

    def glb(self):
        doc = self._finish()
        doc["buffers"] = [{"byteLength": len(self.bin)}]
        js = json.dumps(doc, separators=(",", ":")).encode()
        js += b" " * (-len(js) % 4)
        bin_chunk = bytes(self.bin)
        total = 12 + 8 + len(js) + 8 + len(bin_chunk)
        return (struct.pack("<4sII", b"glTF", 2, total)
                + struct.pack("<I4s", len(js), b"JSON") + js
                + struct.pack("<I4s", len(bin_chunk), b"BIN\x00") + bin_chunk)


# ---------------------------------------------------------------------------------------------
# Room helper: floor, ceiling and four walls as quads facing inward, optionally with openings.


def wall_with_openings(origin, e1, e2, facing, holes):
    """Wall spanning origin + s*e1 + t*e2 (s, t in [0, 1]) minus rectangular `holes` given as
    (s0, s1, t0, t1) fractions; each hole is cut out as a full-height column split into the
    parts below and above it, and the wall between holes is filled in."""
    parts = []
    s_prev = 0.0
    for s0, s1, t0, t1 in sorted(holes):
        if s0 > s_prev:
            parts.append((s_prev, s0, 0.0, 1.0))
        if t0 > 0.0:
            parts.append((s0, s1, 0.0, t0))
        if t1 < 1.0:
            parts.append((s0, s1, t1, 1.0))
        s_prev = s1
    if s_prev < 1.0:
        parts.append((s_prev, 1.0, 0.0, 1.0))
    m = Mesh()
    for s0, s1, t0, t1 in parts:
        corner = add(add(origin, mul(e1, s0)), mul(e2, t0))
        m.extend(quad(corner, mul(e1, s1 - s0), mul(e2, t1 - t0), facing))
    return m


def room_faces(lo, hi):
    """Inward-facing quads of the axis-aligned room lo..hi, keyed floor/ceiling/-x/+x/-z/+z."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    return {
        "floor": quad((x0, y0, z0), (dx, 0, 0), (0, 0, dz), (0, 1, 0)),
        "ceiling": quad((x0, y1, z0), (dx, 0, 0), (0, 0, dz), (0, -1, 0)),
        "-x": quad((x0, y0, z0), (0, 0, dz), (0, dy, 0), (1, 0, 0)),
        "+x": quad((x1, y0, z0), (0, 0, dz), (0, dy, 0), (-1, 0, 0)),
        "-z": quad((x0, y0, z0), (dx, 0, 0), (0, dy, 0), (0, 0, 1)),
        "+z": quad((x0, y0, z1), (dx, 0, 0), (0, dy, 0), (0, 0, -1)),
    }


# ---------------------------------------------------------------------------------------------
# The scenes. Each returns its builder; INTERIORS below gives, per file, the box that each area
# light's front side must face into (used by --check to catch lights that face a wall).


def cornell_box():
    """The classic Cornell box, 1 m on a side, open towards the camera (+Z)."""
    b = GltfBuilder("cornell_box")
    white = b.material("white", base=(0.73, 0.73, 0.73))
    red = b.material("red", base=(0.63, 0.065, 0.05))
    green = b.material("green", base=(0.14, 0.45, 0.091))
    light = b.material("light", base=(0.0, 0.0, 0.0),
                       emission=mul((1.0, 0.85, 0.6), 17.0))
    walls = room_faces((-0.5, 0.0, -0.5), (0.5, 1.0, 0.5))
    b.mesh("floor_ceiling_back", merged(walls["floor"], walls["ceiling"], walls["-z"]), white)
    b.mesh("left_wall", walls["-x"], red)
    b.mesh("right_wall", walls["+x"], green)
    b.mesh("short_box", box_on_floor(0.18, 0.16, (0.3, 0.3, 0.3), math.radians(-17.0)), white)
    b.mesh("tall_box", box_on_floor(-0.17, -0.17, (0.3, 0.6, 0.3), math.radians(17.0)), white)
    # 2 mm below the ceiling so it never shares a plane with it; it faces down into the box.
    b.mesh("light", rect((0.0, 0.998, 0.0), (0, -1, 0), (1, 0, 0), 0.22, 0.22), light)
    b.camera(eye=(0.0, 0.5, 1.85), target=(0.0, 0.5, 0.0), yfov=0.70)
    return b


def veach_mis():
    """Veach's multiple-importance-sampling scene: glossy plates of decreasing roughness that
    reflect a row of spherical lights of growing radius and equal power."""
    b = GltfBuilder("veach_mis")
    dark = b.material("dark_diffuse", base=(0.12, 0.12, 0.12))
    b.mesh("floor", quad((-6.0, 0.0, -3.0), (12.0, 0.0, 0.0), (0.0, 0.0, 10.0), (0, 1, 0)), dark)
    b.mesh("back_wall", quad((-6.0, 0.0, -3.0), (12.0, 0.0, 0.0), (0.0, 6.0, 0.0), (0, 0, 1)), dark)

    camera = (0.0, 1.5, 4.6)
    light_y, light_z = 1.65, -1.6
    # Radii grow by 3x (as in Veach's thesis); radiance falls by 9x so radius^2 * L (hence the
    # power) stays constant: the small light is best found by BSDF sampling on the smooth plate,
    # the large one by light sampling on the rough plate.
    radii = [0.0133, 0.04, 0.12, 0.36]
    colours = [(1.0, 0.62, 0.38), (1.0, 0.93, 0.55), (0.55, 1.0, 0.6), (0.5, 0.7, 1.0)]
    xs = [-1.5, -0.5, 0.5, 1.5]
    for i, (r, col, x) in enumerate(zip(radii, colours, xs)):
        radiance = 0.5 / (r * r)
        mat = b.material("light_%d" % i, base=(0.0, 0.0, 0.0), emission=mul(col, radiance))
        b.mesh("sphere_light_%d" % i, icosphere((x, light_y, light_z), r, 2), mat)

    # Plates from the back (near-mirror) to the front (rough). Each is tilted so that its normal
    # is the half vector between the camera and the centre of the light row, so the camera sees
    # every light reflected in every plate.
    roughness = [0.03, 0.1, 0.25, 0.5]
    centres = [(0.0, 0.80, -0.35), (0.0, 0.62, 0.22), (0.0, 0.46, 0.79), (0.0, 0.32, 1.36)]
    light_centre = (0.0, light_y, light_z)
    for i, (rough, c) in enumerate(zip(roughness, centres)):
        n = normalize(add(normalize(sub(camera, c)), normalize(sub(light_centre, c))))
        ax = (1.0, 0.0, 0.0)
        az = cross(ax, n)          # along the plate's depth, in the y-z plane
        mat = b.material("plate_%d" % i, base=(0.35, 0.35, 0.35), metallic=1.0, roughness=rough)
        b.mesh("plate_%d" % i, oriented_box(c, [ax, n, az], (3.6, 0.02, 0.5)), mat)

    b.camera(eye=camera, target=(0.0, 0.9, 0.0), yfov=0.56)
    return b


# ---------------------------------------------------------------------------------------------
# Reading the files back (for --check). Written against the spec, not against the writer above,
# so a writer bug shows up as a failed check rather than as two matching mistakes.

COMPONENT = {5120: ("b", 1), 5121: ("B", 1), 5122: ("h", 2), 5123: ("H", 2), 5125: ("I", 4),
             5126: ("f", 4)}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


class CheckError(Exception):
    pass


def require(cond, msg):
    if not cond:
        raise CheckError(msg)


def parse_file(data, is_glb):
    if is_glb:
        magic, version, total = struct.unpack_from("<4sII", data, 0)
        require(magic == b"glTF" and version == 2 and total == len(data), "bad GLB header")
        jlen, jtype = struct.unpack_from("<I4s", data, 12)
        require(jtype == b"JSON" and jlen % 4 == 0, "bad GLB JSON chunk")
        doc = json.loads(data[20:20 + jlen].decode())
        off = 20 + jlen
        blen, btype = struct.unpack_from("<I4s", data, off)
        require(btype == b"BIN\x00" and off + 8 + blen == total, "bad GLB BIN chunk")
        buffers = [data[off + 8:off + 8 + blen]]
        require("uri" not in doc["buffers"][0], "GLB buffer 0 must not have a uri")
    else:
        doc = json.loads(data.decode())
        buffers = []
        for buf in doc["buffers"]:
            prefix = "data:application/octet-stream;base64,"
            require(buf["uri"].startswith(prefix), "buffer is not an embedded data URI")
            buffers.append(base64.b64decode(buf["uri"][len(prefix):]))
    require(doc["asset"]["version"] == "2.0", "asset.version must be 2.0")
    require(len(buffers) == 1, "all binary data must be in one buffer")
    for i, buf in enumerate(doc["buffers"]):
        require(len(buffers[i]) >= buf["byteLength"], "buffer %d shorter than byteLength" % i)
    for i, view in enumerate(doc["bufferViews"]):
        end = view.get("byteOffset", 0) + view["byteLength"]
        require(end <= doc["buffers"][view["buffer"]]["byteLength"], "bufferView %d overruns" % i)
    return doc, buffers


def read_accessor(doc, buffers, index):
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    fmt, size = COMPONENT[acc["componentType"]]
    width = WIDTH[acc["type"]]
    stride = view.get("byteStride", size * width)
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    require(start % size == 0, "accessor %d misaligned" % index)
    require(acc.get("byteOffset", 0) + stride * (acc["count"] - 1) + size * width
            <= view["byteLength"], "accessor %d overruns its bufferView" % index)
    buf = buffers[view["buffer"]]
    out = [struct.unpack_from("<%d%s" % (width, fmt), buf, start + k * stride)
           for k in range(acc["count"])]
    for k in range(width):
        column = [v[k] for v in out]
        if "min" in acc:
            require(f32(acc["min"][k]) == f32(min(column)) if fmt == "f" else
                    acc["min"][k] == min(column), "accessor %d: min disagrees with data" % index)
        if "max" in acc:
            require(f32(acc["max"][k]) == f32(max(column)) if fmt == "f" else
                    acc["max"][k] == max(column), "accessor %d: max disagrees with data" % index)
    require("min" in acc and "max" in acc or acc["type"] == "SCALAR",
            "accessor %d: min/max missing" % index)
    return out, acc


def quat_rotate(q, v):
    x, y, z, w = q
    u = (x, y, z)
    t = mul(cross(u, v), 2.0)
    return add(add(v, mul(t, w)), cross(u, t))


def node_transform(node):
    """(translation, rotation, scale) of a node; matrices are not used in these files."""
    require("matrix" not in node, "node matrices are not expected here")
    return (tuple(node.get("translation", (0, 0, 0))), tuple(node.get("rotation", (0, 0, 0, 1))),
            tuple(node.get("scale", (1, 1, 1))))


def world_nodes(doc):
    """Yields (node index, list of TRS from root to node) for every node reachable from the scene."""
    seen = set()
    stack = [(n, []) for n in doc["scenes"][doc.get("scene", 0)]["nodes"]]
    while stack:
        idx, chain = stack.pop()
        require(idx not in seen, "node %d reached twice" % idx)
        seen.add(idx)
        node = doc["nodes"][idx]
        chain = chain + [node_transform(node)]
        yield idx, chain
        stack += [(c, chain) for c in node.get("children", [])]
    require(len(seen) == len(doc["nodes"]), "some nodes are not in the scene")


def apply_point(chain, p):
    for t, r, s in reversed(chain):
        p = add(quat_rotate(r, (p[0] * s[0], p[1] * s[1], p[2] * s[2])), t)
    return p


def apply_dir(chain, d):
    for _, r, _ in reversed(chain):  # uniform/no scale only in these files
        d = quat_rotate(r, d)
    return normalize(d)


def load_scene(data, is_glb):
    """Parses a file into world-space primitives:
    dicts with name, material, pos, nrm, uv (or None), tris (index triples)."""
    doc, buffers = parse_file(data, is_glb)
    prims = []
    cameras = []
    lights = []
    for idx, chain in world_nodes(doc):
        node = doc["nodes"][idx]
        if "camera" in node:
            cameras.append((node["camera"], apply_point(chain, (0, 0, 0)),
                            apply_dir(chain, (0, 0, -1)), apply_dir(chain, (0, 1, 0))))
        ext = node.get("extensions", {}).get("KHR_lights_punctual")
        if ext is not None:
            lights.append((ext["light"], apply_point(chain, (0, 0, 0)),
                           apply_dir(chain, (0, 0, -1))))
        if "mesh" not in node:
            continue
        mesh = doc["meshes"][node["mesh"]]
        for p in mesh["primitives"]:
            require(p.get("mode", 4) == 4, "only triangle lists are used")
            attrs = p["attributes"]
            require("NORMAL" in attrs, "mesh %s has no NORMAL" % mesh.get("name"))
            pos, pacc = read_accessor(doc, buffers, attrs["POSITION"])
            nrm, _ = read_accessor(doc, buffers, attrs["NORMAL"])
            require(len(nrm) == len(pos), "NORMAL count differs from POSITION count")
            uv = None
            if "TEXCOORD_0" in attrs:
                uv, _ = read_accessor(doc, buffers, attrs["TEXCOORD_0"])
                require(len(uv) == len(pos), "TEXCOORD_0 count differs from POSITION count")
            idx_data, iacc = read_accessor(doc, buffers, p["indices"])
            require(iacc["componentType"] in (UINT16, UINT32), "indices must be uint16/uint32")
            flat = [v[0] for v in idx_data]
            require(len(flat) % 3 == 0, "index count not a multiple of 3")
            require(max(flat) < len(pos), "index out of range in %s" % mesh.get("name"))
            for n in nrm:
                require(abs(length(n) - 1.0) < 1e-4, "non-unit normal in %s" % mesh.get("name"))
            require(0 <= p["material"] < len(doc["materials"]), "material out of range")
            prims.append({"name": mesh.get("name", "?"), "material": p["material"],
                          "pos": [apply_point(chain, v) for v in pos],
                          "nrm": [apply_dir(chain, v) for v in nrm], "uv": uv,
                          "tris": [tuple(flat[t:t + 3]) for t in range(0, len(flat), 3)]})
    return doc, buffers, prims, cameras, lights


def log_spaced(lo, hi, count):
    return [lo * (hi / lo) ** (k / (count - 1)) for k in range(count)]


def many_lights():
    """A 10 x 3 x 8 m room split by three partitions with doorways into four areas; 34 small
    lights whose strengths span three orders of magnitude, many of them out of the camera's view
    so that they reach what it sees only through doorways, or not at all."""
    b = GltfBuilder("many_lights")
    wall = b.material("wall", base=(0.7, 0.7, 0.68))
    floor_mat = b.material("floor", base=(0.45, 0.4, 0.35))
    partition_mat = b.material("partition", base=(0.75, 0.73, 0.7))
    furniture = [b.material("furniture_wood", base=(0.5, 0.32, 0.18)),
                 b.material("furniture_blue", base=(0.15, 0.25, 0.55)),
                 b.material("furniture_grey", base=(0.4, 0.4, 0.4))]

    lo, hi = (-5.0, 0.0, -4.0), (5.0, 3.0, 4.0)
    room = room_faces(lo, hi)
    b.mesh("floor", room["floor"], floor_mat)
    b.mesh("walls_ceiling", merged(room["ceiling"], room["-x"], room["+x"], room["-z"],
                                   room["+z"]), wall)

    # Partitions are 0.12 m thick boxes with a 1 x 2.1 m doorway each:
    #   west  (x = -2): z in [-4, 4], doorway z in [0.6, 1.6]      -> area A behind it (x < -2)
    #   east  (x = +2): z in [-4, 4], doorway z in [-2.6, -1.6]    -> area C behind it (x > 2)
    #   north (z = -1.5): x in [-2, 2], doorway x in [-0.5, 0.5]  -> area D behind it (z < -1.5)
    # The camera stands in area B (-2 < x < 2, z > -1.5).
    h, door_h, th = 3.0, 2.1, 0.06
    parts = Mesh()
    for z0, z1 in ((-4.0, 0.6), (1.6, 4.0)):
        parts.extend(box_between((-2 - th, 0, z0), (-2 + th, h, z1), skip=("-y", "+y")))
    parts.extend(box_between((-2 - th, door_h, 0.6), (-2 + th, h, 1.6), skip=("+y",)))
    for z0, z1 in ((-4.0, -2.6), (-1.6, 4.0)):
        parts.extend(box_between((2 - th, 0, z0), (2 + th, h, z1), skip=("-y", "+y")))
    parts.extend(box_between((2 - th, door_h, -2.6), (2 + th, h, -1.6), skip=("+y",)))
    for x0, x1 in ((-2 + th, -0.5), (0.5, 2 - th)):
        parts.extend(box_between((x0, 0, -1.5 - th), (x1, h, -1.5 + th), skip=("-y", "+y")))
    parts.extend(box_between((-0.5, door_h, -1.5 - th), (0.5, h, -1.5 + th), skip=("+y",)))
    b.mesh("partitions", parts, partition_mat)

    furniture_boxes = [  # (x, z, size, yaw, material) -- a table and cabinets in every area
        (0.5, 0.3, (1.2, 0.75, 0.7), 0.3, 0), (-1.4, -0.6, (0.6, 1.8, 0.5), 0.0, 1),
        (1.5, 2.4, (0.5, 0.5, 0.5), 0.7, 2), (-3.5, -2.0, (1.2, 0.8, 0.7), 0.2, 0),
        (3.4, 1.5, (0.6, 1.5, 1.2), -0.2, 1), (0.0, -3.0, (1.6, 0.9, 0.6), 0.0, 2),
        (-3.8, 2.8, (0.7, 0.7, 0.7), 0.5, 2), (3.6, -3.2, (1.0, 0.6, 0.6), 0.1, 0)]
    for k, (x, z, size, yaw, mat) in enumerate(furniture_boxes):
        b.mesh("furniture_%d" % k, box_on_floor(x, z, size, yaw), furniture[mat])

    # Light mounts: (centre, normal it faces, tangent, size). Ceiling lights sit 2 mm below the
    # ceiling facing down; wall lights 2 mm in front of their wall facing away from it.
    ceil_y, off = 3.0 - 0.002, 0.002
    mounts = []
    for x, z in ((-4.0, -3.0), (-3.0, -0.5), (-4.0, 1.5), (-3.0, 3.3),     # area A
                 (3.0, -3.0), (4.0, -0.5), (3.0, 1.8), (4.2, 3.3),       # area C
                 (-1.2, -3.3), (0.0, -2.4), (1.2, -3.3),                  # area D
                 (-1.0, 0.0), (1.0, 0.0), (-1.0, 2.0), (1.0, 2.0), (0.0, 3.3)):  # area B
        mounts.append(((x, ceil_y, z), (0, -1, 0), (1, 0, 0), 0.4))
    for z in (-3.0, -1.0, 1.0, 3.0):                        # area A: west wall of the room
        mounts.append(((-5.0 + off, 2.2, z), (1, 0, 0), (0, 0, 1), 0.3))
    for z in (-3.0, -0.3, 2.5):                              # area C: east wall of the room
        mounts.append(((5.0 - off, 2.2, z), (-1, 0, 0), (0, 0, 1), 0.3))
    for x in (-1.2, 0.0, 1.2):                               # area D: north wall, partly visible
        mounts.append(((x, 1.6, -4.0 + off), (0, 0, 1), (1, 0, 0), 0.3))
    for z in (-0.5, 2.5):                                    # area B: west partition, B side
        mounts.append(((-2 + th + off, 2.0, z), (1, 0, 0), (0, 0, 1), 0.3))
    for z in (0.5, 2.8):                                     # area B: east partition, B side
        mounts.append(((2 - th - off, 2.0, z), (-1, 0, 0), (0, 0, 1), 0.3))
    for x in (-1.3, 1.3):                                    # area B: north partition, B side
        mounts.append(((x, 2.3, -1.5 + th + off), (0, 0, 1), (1, 0, 0), 0.3))
    for x in (-1.2, 1.2):                                    # area D: north partition, D side
        mounts.append(((x, 2.3, -1.5 - th - off), (0, 0, -1), (1, 0, 0), 0.3))

    palette = [(1.0, 0.85, 0.6), (0.75, 0.85, 1.0), (1.0, 0.3, 0.2), (0.3, 1.0, 0.35),
               (0.3, 0.45, 1.0), (1.0, 0.6, 0.15), (1.0, 1.0, 1.0)]
    strengths = log_spaced(0.1, 100.0, len(mounts))
    # A fixed permutation (7 is coprime with the count) mixes bright and dim lights over the
    # areas, deterministically.
    for k, (centre, normal, tangent, size) in enumerate(mounts):
        strength = strengths[(k * 7) % len(mounts)]
        colour = palette[(k * 3) % len(palette)]
        mat = b.material("light_%02d" % k, base=(0.0, 0.0, 0.0), emission=mul(colour, strength))
        b.mesh("light_%02d" % k, rect(centre, normal, tangent, size, size), mat)

    b.camera(eye=(1.5, 1.6, 3.85), target=(-0.5, 1.15, -1.5), yfov=1.0)
    return b


def cove_light(name, material, wall_x_or_z, along, inward, span):
    """A lamp on a ledge near the ceiling that shines upwards, with a lip on the room side: it
    lights the ceiling and the top of the wall directly, and the rest of the room only through
    them. `inward` is +1/-1 along the axis the wall is perpendicular to ('x' or 'z' = `along`
    gives the axis the ledge runs along)."""
    ledge_depth, ledge_y, lip_top = 0.4, 2.2, 2.45

    def frame(d, t, y):  # d: distance from the wall into the room, t: position along the wall
        return (wall_x_or_z + inward * d, y, t) if along == "z" else (t, y, wall_x_or_z + inward * d)

    def between(d0, d1, y0, y1, t0, t1):
        a, c = frame(d0, t0, y0), frame(d1, t1, y1)
        return box_between(tuple(min(a[k], c[k]) for k in range(3)),
                           tuple(max(a[k], c[k]) for k in range(3)))

    t0, t1 = span
    fixture = merged(between(0.0, ledge_depth, ledge_y - 0.06, ledge_y, t0, t1),
                     between(ledge_depth - 0.04, ledge_depth, ledge_y, lip_top, t0, t1))
    lamp_centre = frame(0.18, 0.5 * (t0 + t1), ledge_y + 0.002)
    tangent = (0, 0, 1) if along == "z" else (1, 0, 0)
    lamp = rect(lamp_centre, (0, 1, 0), tangent, t1 - t0 - 0.2, 0.25)
    return fixture, (name, lamp, material)


def indirect_rgb():
    """A white room lit only by red, green and blue cove lights hidden on ledges below the
    ceiling: the camera sees the lamps' light almost entirely after one or more bounces."""
    b = GltfBuilder("indirect_rgb")
    white = b.material("white", base=(0.8, 0.8, 0.8))
    floor_mat = b.material("floor", base=(0.7, 0.68, 0.65))
    objects = b.material("objects", base=(0.85, 0.85, 0.85))
    ledge = b.material("ledge", base=(0.75, 0.75, 0.75))
    room = room_faces((-3.0, 0.0, -3.0), (3.0, 3.0, 3.0))
    b.mesh("floor", room["floor"], floor_mat)
    b.mesh("walls_ceiling", merged(room["ceiling"], room["-x"], room["+x"], room["-z"],
                                   room["+z"]), white)

    lamps = []
    strength = 12.0
    red = b.material("lamp_red", base=(0, 0, 0), emission=mul((1.0, 0.08, 0.04), strength))
    green = b.material("lamp_green", base=(0, 0, 0), emission=mul((0.08, 1.0, 0.1), strength))
    blue = b.material("lamp_blue", base=(0, 0, 0), emission=mul((0.1, 0.2, 1.0), strength))
    fixtures = Mesh()
    for args in (("lamp_red", red, -3.0, "z", 1.0, (-2.6, 2.0)),
                 ("lamp_green", green, 3.0, "z", -1.0, (-2.6, 2.0)),
                 ("lamp_blue", blue, -3.0, "x", 1.0, (-2.0, 2.0))):
        fixture, lamp = cove_light(*args)
        fixtures.extend(fixture)
        lamps.append(lamp)
    b.mesh("ledges", fixtures, ledge)
    for name, mesh, mat in lamps:
        b.mesh(name, mesh, mat)

    b.mesh("box", box_on_floor(-0.9, -0.8, (0.8, 0.8, 0.8), 0.4), objects)
    b.mesh("tall_box", box_on_floor(1.3, -1.5, (0.5, 1.6, 0.5), -0.3), objects)
    b.mesh("sphere", icosphere((0.8, 0.5, 0.0), 0.5, 3), objects)
    b.camera(eye=(0.0, 1.4, 2.85), target=(0.0, 1.2, -3.0), yfov=0.95)
    return b


def checker_pixel(x, y):
    """64 x 64 texture: 8 x 8 checker cells, light cells carrying a colour gradient so that the
    orientation and the repetition of the texture are visible."""
    if ((x // 8) + (y // 8)) % 2 == 0:
        return (235, 235 - 2 * x, 150 + 1 * y)
    return (40, 40 + y, 40 + x)


def metal_rough_pixel(x, y):
    """32 x 32: horizontal bands (along v) alternating rough dielectric and polished metal; R is
    unused (occlusion would live there), G = roughness, B = metalness, all linear."""
    band = (y // 4) % 2
    return (255, 200, 0) if band == 0 else (255, 40, 255)


def emissive_pixel(x, y):
    """32 x 16 sign: a warm-to-cool gradient with a dark frame and a dark stripe."""
    if x in (0, 31) or y in (0, 15) or y == 8:
        return (10, 10, 10)
    return (255, 120 + 4 * x, 255 - 8 * x)


def textured():
    b = GltfBuilder("textured")
    checker = b.image("checker", png_bytes(64, 64, checker_pixel))
    metal_rough = b.image("metal_rough", png_bytes(32, 32, metal_rough_pixel))
    sign = b.image("sign", png_bytes(32, 16, emissive_pixel))
    smooth = b.sampler(LINEAR, LINEAR_MIPMAP_LINEAR)
    crisp = b.sampler(NEAREST, NEAREST)
    checker_tex = b.texture(checker, smooth)
    mr_tex = b.texture(metal_rough, crisp)
    sign_tex = b.texture(sign, smooth)

    floor_mat = b.material("checker_floor", base=(1.0, 1.0, 1.0), base_tex=checker_tex)
    wall = b.material("wall", base=(0.7, 0.7, 0.7))
    banded = b.material("banded_sphere", base=(0.95, 0.75, 0.4), metallic=1.0, roughness=1.0,
                        mr_tex=mr_tex)
    sign_mat = b.material("sign", base=(0.0, 0.0, 0.0), emission=(4.0, 4.0, 4.0),
                          emissive_tex=sign_tex)
    light = b.material("light", base=(0.0, 0.0, 0.0), emission=mul((1.0, 0.95, 0.88), 20.0))

    # Floor 6 x 6 m with texture coordinates 0..4: the 64 x 64 texture repeats four times each way.
    b.mesh("floor", quad((-3.0, 0.0, -3.0), (6.0, 0, 0), (0, 0, 6.0), (0, 1, 0), (4.0, 4.0)),
           floor_mat)
    b.mesh("back_wall", quad((-3.0, 0.0, -2.0), (6.0, 0, 0), (0, 3.0, 0), (0, 0, 1)), wall)
    b.mesh("sphere", uv_sphere((0.0, 0.55, -0.4), 0.55, 24, 48), banded)
    b.mesh("sign", rect((0.0, 1.9, -2.0 + 0.002), (0, 0, 1), (1, 0, 0), 1.6, 0.8, (1.0, 1.0)),
           sign_mat)
    b.mesh("light", rect((0.8, 2.8, 0.8), (0, -1, 0), (1, 0, 0), 0.6, 0.6), light)
    b.camera(eye=(0.0, 2.1, 3.9), target=(0.0, 0.7, -0.6), yfov=0.75)
    return b


def punctual():
    """A closed room lit by a point light, a spot light, a small area light and a directional
    light (the sun) that can only come in through a window in the west wall."""
    b = GltfBuilder("punctual")
    white = b.material("white", base=(0.75, 0.75, 0.75))
    floor_mat = b.material("floor", base=(0.55, 0.5, 0.45))
    box_mat = b.material("box", base=(0.6, 0.3, 0.2))
    light = b.material("light", base=(0.0, 0.0, 0.0), emission=mul((0.8, 0.9, 1.0), 40.0))
    lo, hi = (-2.5, 0.0, -2.5), (2.5, 2.6, 2.5)
    room = room_faces(lo, hi)
    # The west wall (x = -2.5) spans z (s, via e1) and y (t, via e2); the window spans
    # z in [-1.2, 0.4] and y in [0.8, 2.0].
    west = wall_with_openings((-2.5, 0.0, -2.5), (0, 0, 5.0), (0, 2.6, 0), (1, 0, 0),
                              [(1.3 / 5.0, 2.9 / 5.0, 0.8 / 2.6, 2.0 / 2.6)])
    b.mesh("floor", room["floor"], floor_mat)
    b.mesh("walls_ceiling", merged(room["ceiling"], west, room["+x"], room["-z"], room["+z"]),
           white)
    b.mesh("box", box_on_floor(0.9, -1.0, (0.7, 0.7, 0.7), 0.35), box_mat)
    b.mesh("tall_box", box_on_floor(-1.4, -1.9, (0.5, 1.3, 0.5), -0.2), box_mat)
    b.mesh("area_light", rect((-1.2, 2.598, 1.2), (0, -1, 0), (1, 0, 0), 0.3, 0.3), light)

    b.punctual_light("point", "point", (1.0, 1.0, 1.0), 3.0, position=(1.2, 1.9, -1.2))
    b.punctual_light("spot", "spot", (1.0, 0.85, 0.6), 12.0, position=(0.4, 2.5, 1.0),
                     direction=(-0.1, -1.0, -0.5), inner=0.25, outer=0.4)
    # Sun: travels towards +x and down; through the window it lands on the floor around
    # x in [-1.5, 0].
    b.punctual_light("sun", "directional", (1.0, 0.95, 0.85), 3.0, direction=(1.0, -0.8, 0.15))
    b.camera(eye=(0.3, 1.4, 2.4), target=(-0.5, 0.9, -2.5), yfov=1.0)
    return b


# ---------------------------------------------------------------------------------------------
# The shipped files, and what --check expects of them.

SCENES = [  # (file name, builder function, container)
    ("cornell_box.gltf", cornell_box, "gltf"),
    ("veach_mis.gltf", veach_mis, "gltf"),
    ("many_lights.gltf", many_lights, "gltf"),
    ("indirect_rgb.gltf", indirect_rgb, "gltf"),
    ("textured.glb", textured, "glb"),
    ("punctual.gltf", punctual, "gltf"),
]

# The region each planar light must face into (a point 1 cm in front of it lies inside), so a
# light mounted under a ceiling cannot silently face the ceiling. None: no planar lights.
INTERIORS = {
    "cornell_box.gltf": ((-0.5, 0.0, -0.5), (0.5, 1.0, 0.5)),
    "veach_mis.gltf": None,
    "many_lights.gltf": ((-5.0, 0.0, -4.0), (5.0, 3.0, 4.0)),
    "indirect_rgb.gltf": ((-3.0, 0.0, -3.0), (3.0, 3.0, 3.0)),
    "textured.glb": ((-3.0, 0.0, -2.0), (3.0, 2.8, 3.0)),
    "punctual.gltf": ((-2.5, 0.0, -2.5), (2.5, 2.6, 2.5)),
}

# Triangle counts, to notice unintended changes to the geometry.
EXPECTED_TRIANGLES = {
    "cornell_box.gltf": 32,     # 5 walls, 2 boxes without bottoms, the light
    "veach_mis.gltf": 1332,     # floor, wall, 4 icospheres of 320, 4 plates of 12
    "many_lights.gltf": 238,    # room, partitions, 8 furniture boxes, 34 lights
    "indirect_rgb.gltf": 1390,  # room, 3 ledges, 3 lamps, 2 boxes, a 1280-triangle icosphere
    "textured.glb": 2216,       # floor, wall, a 24 x 48 UV sphere, sign, light
    "punctual.gltf": 40,        # room with a window, 2 boxes, the area light
}

# How many lights the camera must see directly (a point of the light inside a 4:3 frame and
# unoccluded) and how many must be hidden from it: (least visible, least hidden).
VISIBILITY = {
    "cornell_box.gltf": (1, 0),
    "veach_mis.gltf": (4, 0),
    "many_lights.gltf": (8, 16),
    "indirect_rgb.gltf": (0, 3),   # the whole point: every lamp is hidden
    "textured.glb": (1, 0),
    "punctual.gltf": (0, 0),
}

MAX_FILE_BYTES = 300 * 1024


def build(entry):
    name, fn, container = entry
    b = fn()
    return b.glb() if container == "glb" else b.gltf()


def write_all():
    for entry in SCENES:
        data = build(entry)
        with open(os.path.join(HERE, entry[0]), "wb") as f:
            f.write(data)
        print("wrote scenes/%s (%d bytes)" % (entry[0], len(data)))


def check_png(data):
    """Verifies signature, chunk CRCs and that the image data has the size IHDR promises."""
    require(data[:8] == b"\x89PNG\r\n\x1a\n", "image is not a PNG")
    off, idat, ihdr = 8, b"", None
    while off < len(data):
        n, kind = struct.unpack_from(">I4s", data, off)
        body = data[off + 8:off + 8 + n]
        (crc,) = struct.unpack_from(">I", data, off + 8 + n)
        require(zlib.crc32(kind + body) & 0xFFFFFFFF == crc, "PNG chunk CRC mismatch")
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        off += 12 + n
    require(ihdr is not None and ihdr[2] == 8 and ihdr[3] in (2, 6), "PNG must be 8-bit RGB(A)")
    w, h, channels = ihdr[0], ihdr[1], 3 if ihdr[3] == 2 else 4
    raw = zlib.decompress(idat)
    require(len(raw) == h * (1 + w * channels), "PNG data size disagrees with IHDR")
    require(all(raw[y * (1 + w * channels)] <= 4 for y in range(h)), "bad PNG filter byte")
    return w, h


def ray_hit_distance(origin, direction, prims, skip_prim=None):
    """Nearest positive hit of a ray against every triangle (Moller-Trumbore), or None."""
    best = None
    for pi, p in enumerate(prims):
        if pi == skip_prim:
            continue
        for a, b, c in p["tris"]:
            A, B, C = p["pos"][a], p["pos"][b], p["pos"][c]
            e1, e2 = sub(B, A), sub(C, A)
            pv = cross(direction, e2)
            det = dot(e1, pv)
            if abs(det) < 1e-14:
                continue
            tv = sub(origin, A)
            u = dot(tv, pv) / det
            if u < 0.0 or u > 1.0:
                continue
            qv = cross(tv, e1)
            v = dot(direction, qv) / det
            if v < 0.0 or u + v > 1.0:
                continue
            t = dot(e2, qv) / det
            if t > 1e-6 and (best is None or t < best):
                best = t
    return best


def inside(box, p, margin=0.0):
    lo, hi = box
    return all(lo[k] - margin <= p[k] <= hi[k] + margin for k in range(3))


def emission_of(mat):
    factor = mat.get("emissiveFactor", [0.0, 0.0, 0.0])
    strength = mat.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get(
        "emissiveStrength", 1.0)
    return [c * strength for c in factor]


def check_materials(doc, name):
    used = set(doc.get("extensionsUsed", []))
    require("KHR_materials_emissive_strength" not in doc.get("extensionsRequired", []),
            "emissive strength must not be required")
    textures = doc.get("textures", [])
    for m in doc["materials"]:
        for ext in m.get("extensions", {}):
            require(ext in used, "%s: material extension %s not in extensionsUsed" % (name, ext))
        es = m.get("extensions", {}).get("KHR_materials_emissive_strength")
        if es is not None:
            require(abs(max(m["emissiveFactor"]) - 1.0) < 1e-6 and es["emissiveStrength"] > 1.0,
                    "%s: emissive colour should be normalised when a strength is used" % name)
        pbr = m.get("pbrMetallicRoughness", {})
        for key, holder in (("baseColorTexture", pbr), ("metallicRoughnessTexture", pbr),
                            ("emissiveTexture", m)):
            if key in holder:
                require(0 <= holder[key]["index"] < len(textures), "texture index out of range")
    for t in textures:
        require(0 <= t["source"] < len(doc["images"]), "texture source out of range")
        require(0 <= t["sampler"] < len(doc["samplers"]), "texture sampler out of range")
    for ext in doc.get("extensions", {}):
        require(ext in used, "%s: extension %s not in extensionsUsed" % (name, ext))
    for ext in used:
        require(ext in ("KHR_materials_emissive_strength", "KHR_lights_punctual"),
                "%s: unexpected extension %s" % (name, ext))
    require(("KHR_lights_punctual" in used) == (name == "punctual.gltf"),
            "%s: KHR_lights_punctual belongs to punctual.gltf only" % name)


def check_winding(prims, name):
    """Every triangle's geometric normal (from its winding) must agree with its NORMAL
    attribute: exactly for flat faces, on the same side for smooth ones. Returns the smallest
    cosine seen."""
    worst = 1.0
    for p in prims:
        for tri in p["tris"]:
            A, B, C = (p["pos"][i] for i in tri)
            g = cross(sub(B, A), sub(C, A))
            require(length(g) > 1e-12, "%s/%s: degenerate triangle" % (name, p["name"]))
            g = normalize(g)
            ns = [p["nrm"][i] for i in tri]
            mean = normalize(add(add(ns[0], ns[1]), ns[2]))
            cos = dot(g, mean)
            flat = all(dot(ns[0], n) > 0.999999 for n in ns)
            require(cos > (0.9999 if flat else 0.0),
                    "%s/%s: winding disagrees with NORMAL (cos %.4f)" % (name, p["name"], cos))
            worst = min(worst, cos)
    return worst


def check_emitters(doc, prims, name):
    """Planar lights: their front must face the scene's interior and must not be blocked right
    in front (a light facing the ceiling it hangs under would be). Closed lights (spheres):
    every face turns outwards."""
    interior = INTERIORS[name]
    count = 0
    for pi, p in enumerate(prims):
        mat = doc["materials"][p["material"]]
        if max(emission_of(mat)) <= 0.0 and "emissiveTexture" not in mat:
            continue
        count += 1
        require(not mat.get("doubleSided", False), "%s/%s: lights are one-sided" % (name, p["name"]))
        faces = []
        for tri in p["tris"]:
            A, B, C = (p["pos"][i] for i in tri)
            faces.append((normalize(cross(sub(B, A), sub(C, A))), mul(add(add(A, B), C), 1 / 3)))
        centre = tuple(sum(v[k] for v in p["pos"]) / len(p["pos"]) for k in range(3))
        if all(dot(f[0], faces[0][0]) > 0.9999 for f in faces):
            n = faces[0][0]
            require(interior is not None and inside(interior, add(centre, mul(n, 0.01))),
                    "%s/%s: light faces out of the room" % (name, p["name"]))
            hit = ray_hit_distance(add(centre, mul(n, 1e-5)), n, prims, skip_prim=pi)
            require(hit is None or hit > 0.05,
                    "%s/%s: light is blocked right in front (%.4f m)" % (name, p["name"], hit or 0))
        else:
            for g, c in faces:
                require(dot(g, sub(c, centre)) > 0.0,
                        "%s/%s: closed light has an inward face" % (name, p["name"]))
    return count


def camera_sees(camera, yfov, point, prims):
    """Whether `point` is inside the camera's 4:3 frame and nothing lies between them."""
    _, eye, forward, up = camera
    right = cross(forward, up)
    d = sub(point, eye)
    z = dot(d, forward)
    if z <= 0.0:
        return False
    half = math.tan(yfov / 2.0)
    if abs(dot(d, right) / z) > half * 4.0 / 3.0 or abs(dot(d, up) / z) > half:
        return False
    dist = length(d)
    hit = ray_hit_distance(eye, normalize(d), prims)
    return hit is None or hit > dist - 1e-4


def check_light_visibility(doc, prims, camera, name):
    """Counts the lights the camera sees directly (their centre or a point near a corner)."""
    yfov = doc["cameras"][0]["perspective"]["yfov"]
    visible = hidden = 0
    for p in prims:
        mat = doc["materials"][p["material"]]
        if max(emission_of(mat)) <= 0.0:
            continue
        centre = tuple(sum(v[k] for v in p["pos"]) / len(p["pos"]) for k in range(3))
        samples = [centre] + [add(centre, mul(sub(v, centre), 0.9)) for v in p["pos"][:4]]
        if p["uv"] is None and len(p["pos"]) > 4:  # a sphere: its points nearest the camera
            samples = [add(centre, mul(normalize(sub(camera[1], centre)),
                                       0.99 * length(sub(p["pos"][0], centre))))]
        if any(camera_sees(camera, yfov, s, prims) for s in samples):
            visible += 1
        else:
            hidden += 1
    least_visible, least_hidden = VISIBILITY[name]
    require(visible >= least_visible and hidden >= least_hidden,
            "%s: camera sees %d lights and not %d; wanted at least %d and %d"
            % (name, visible, hidden, least_visible, least_hidden))
    return visible, hidden


def check_punctual(doc, lights, prims, name):
    defs = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    require(len(lights) == len(defs), "%s: every punctual light needs one node" % name)
    for index, position, direction in lights:
        light = defs[index]
        require(light["intensity"] > 0.0, "punctual light without intensity")
        if light["type"] == "spot":
            s = light["spot"]
            require(0.0 <= s["innerConeAngle"] < s["outerConeAngle"] <= math.pi / 2,
                    "%s: spot cone angles out of order" % name)
        if light["type"] in ("point", "spot"):
            require(inside(INTERIORS[name], position), "%s: %s light outside the room" % (
                name, light["name"]))
        if light["type"] == "spot":
            hit = ray_hit_distance(position, direction, prims)
            require(hit is not None, "%s: the spot light points at nothing" % name)
        if light["type"] == "directional":
            # The sun must reach part of the floor through the window, and only part of it.
            lo, hi = INTERIORS[name]
            lit = total = 0
            for i in range(20):
                for k in range(20):
                    p = (lo[0] + (hi[0] - lo[0]) * (i + 0.5) / 20, lo[1] + 1e-4,
                         lo[2] + (hi[2] - lo[2]) * (k + 0.5) / 20)
                    total += 1
                    lit += ray_hit_distance(p, neg(direction), prims) is None
            require(0 < lit < total // 2, "%s: sun reaches %d/%d floor samples" % (name, lit, total))
            print("    %s: sun reaches %d%% of the floor through the window"
                  % (name, round(100 * lit / total)))


def check_file(entry):
    name, _, container = entry
    path = os.path.join(HERE, name)
    with open(path, "rb") as f:
        data = f.read()
    require(data == build(entry), "%s is out of date: run scenes/make_scenes.py" % name)
    require(len(data) <= MAX_FILE_BYTES, "%s is larger than %d bytes" % (name, MAX_FILE_BYTES))
    doc, buffers, prims, cameras, lights = load_scene(data, container == "glb")

    require(len(doc.get("cameras", [])) == 1 and len(cameras) == 1,
            "%s: needs exactly one camera and one camera node" % name)
    yfov = doc["cameras"][0]["perspective"]["yfov"]
    require(0.1 < yfov < 2.5, "%s: implausible yfov" % name)
    _, eye, forward, _ = cameras[0]
    require(ray_hit_distance(eye, forward, prims) is not None, "%s: camera looks at nothing" % name)

    check_materials(doc, name)
    for img in doc.get("images", []):
        view = doc["bufferViews"][img["bufferView"]]
        start = view.get("byteOffset", 0)
        check_png(buffers[view["buffer"]][start:start + view["byteLength"]])
    for p in prims:
        mat = doc["materials"][p["material"]]
        textured_mat = ("emissiveTexture" in mat or any(
            k in mat.get("pbrMetallicRoughness", {})
            for k in ("baseColorTexture", "metallicRoughnessTexture")))
        require(not textured_mat or p["uv"] is not None,
                "%s/%s: textured mesh without TEXCOORD_0" % (name, p["name"]))

    worst = check_winding(prims, name)
    emitters = check_emitters(doc, prims, name)
    check_punctual(doc, lights, prims, name)
    visible, hidden = check_light_visibility(doc, prims, cameras[0], name)
    triangles = sum(len(p["tris"]) for p in prims)
    expected = EXPECTED_TRIANGLES.get(name)
    require(expected == triangles, "%s: %d triangles, expected %s (update EXPECTED_TRIANGLES "
            "if the change is intended)" % (name, triangles, expected))
    print("ok %-18s %5d triangles %3d primitives %3d materials %2d area lights (%d seen, %d "
          "hidden) %d punctual %d textures %6d bytes, winding cos >= %.3f"
          % (name, triangles, len(prims), len(doc["materials"]), emitters, visible, hidden,
             len(lights), len(doc.get("textures", [])), len(data), worst))


def main(argv):
    if argv[1:] == ["--check"]:
        failed = 0
        for entry in SCENES:
            try:
                check_file(entry)
            except (CheckError, OSError, ValueError, KeyError, struct.error) as e:
                failed += 1
                print("FAIL %s: %s" % (entry[0], e))
        return 1 if failed else 0
    if argv[1:]:
        print(__doc__)
        return 2
    write_all()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
