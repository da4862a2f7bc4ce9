#!/usr/bin/env python3
"""Converts a SeeSharp scene folder (JSON + PLY meshes, textures) to glTF 2.0, and checks the results.

    python3 scenes/paper/convert_seesharp.py SRC/Scenes/VeachMIS    # writes scenes/paper/VeachMIS/
    python3 scenes/paper/convert_seesharp.py --check                 # validates every shipped scene
    python3 scenes/paper/convert_seesharp.py --check DIR             # ... or those under DIR

The scenes are those of the reference implementation of "Controlled mixture sampling" (GitHub
qingqhua/ControlledMixtureSampling, folder Scenes/). Each converted scene is written to
scenes/paper/<Scene>/<Scene>.gltf + <Scene>.bin (textures are JPEG images inside the .bin), with
the source's LICENSE.txt copied beside it. Needs Debian's python3 with numpy and, for textures,
PIL (python3-pil); without PIL textured materials get a constant grey 0.5 and the script
says so.

Source: the snapshot converted is commit 65ebd1ca24fd83c7c16322cf2e2f129bd69fb3bb of
qingqhua/ControlledMixtureSampling. Three of its files were absent from that snapshot (large
blobs): Bathroom's Meshes/PlantSucculentEcheveria001.0.ply (left out) and RGBSofa's two
modern_coffee_table_02 PNG textures (grey 0.5); every such change is listed in the scene's
NOTES.txt. DiningRoom2 is converted without its environment map (mixtrace has no environment
lighting yet): its two lamps light it, the window stays dark, so it is not the paper's image and
stays out of the paper's table until environment lighting exists. GlossyManyLights is not one of
the paper's table scenes and is not shipped.

Conventions followed (read from SeeSharp's loader, GitHub pgrit/SeeSharp: SeeSharp/IO/JsonScene.cs,
PlyFile.cs, ObjConverter.cs, Cameras/PerspectiveCamera.cs, Shading/Materials/GenericMaterial.cs,
Shading/Emitters/DiffuseEmitter.cs):

* Units and handedness. SeeSharp's world is right-handed, +Y up, and the scenes are in metres
  (exported from Blender). glTF is the same, so positions and normals are copied unchanged.
* Transforms. The objects of these scenes carry no transform: PLY/OBJ vertices are already in
  world space, so mesh nodes get none. Named transforms (used by the camera) are SeeSharp's
  System.Numerics row-vector product Scale * YawPitchRoll(rot.y, rot.x, rot.z) * Translation,
  angles in degrees. In column-vector form that is T * Ry(yaw) * Rx(pitch) * Rz(roll) * S: roll
  about Z first, then pitch about X, then yaw about Y. A "matrix" entry (16 numbers, row-vector
  layout, translation in the last row) replaces the TRS. The result is written as the camera
  node's glTF `matrix` (column-major, which is the same 16 numbers in the same order).
* The camera. SeeSharp's PerspectiveCamera looks down its local -Z with +Y up and +X right in a
  right-handed frame, as a glTF camera does; its `fov` is the full vertical angle in degrees,
  written as `yfov` in radians. No aspectRatio: mixtrace takes it from the image. The camera's
  thin lens is unused by these scenes (pinhole).
* Materials. SeeSharp's "generic" material (a Disney-like BSDF) maps to glTF metallic-roughness:
  baseColor -> baseColorFactor or baseColorTexture, metallic -> metallicFactor, roughness ->
  roughnessFactor unchanged. Both renderers use GGX with alpha = roughness^2; SeeSharp clamps
  alpha to at least 0.001 (GenericMaterial.ComputeLocalParams), mixtrace to at least 0.002
  (shaders/shared/constants.h, kMinAlpha), so a SeeSharp roughness below 0.045 renders as
  roughness 0.045 here (VeachMIS's sharpest plate: roughness 0.01). A "diffuse" material
  (SeeSharp's pure Lambertian DiffuseMaterial) becomes roughness 1, metallic 0: glTF's BRDF adds
  a rough specular layer of Fresnel weight 0.04 at normal incidence on top of the diffuse one.
  Dropped, since mixtrace's BRDF is glTF's: the IOR (SeeSharp's F0 for IOR 1.45 is 0.034,
  glTF's fixed 0.04), specularTintStrength, anisotropic, diffuseTransmittance, thin, and
  specularTransmittance (a transmissive material, e.g. ModernHall's glass, becomes an opaque
  dielectric; the script lists each one it changes). Non-emissive materials are
  `doubleSided: true` (SeeSharp shades both sides).
* Emitters. SeeSharp makes every triangle of an emissive mesh a DiffuseEmitter that emits the
  material's (or the object's) `emission` radiance on the side of the interpolated *shading*
  normal only. So emissive materials get `doubleSided: false` (mixtrace decides the emitting side
  by the winding, counter-clockwise = front) and every emissive triangle whose winding disagrees
  with its vertex normals (sum of the three NORMALs . geometric normal < 0) has two indices
  swapped; the script reports how many it flipped. A radiance above 1 is written as
  emissiveFactor normalised to a largest component of 1 times KHR_materials_emissive_strength.
  Glossy emitters (emissionIsGlossy) do not occur in these scenes and are refused.
* Meshes. PLY (binary little-endian and ASCII; polygons fan-triangulated as SeeSharp does) and
  OBJ (v/vt/vn, usemtl; one primitive per material). PLY texture coordinates are used as they are
  (SeeSharp and glTF both put v = 0 at the image's top row); OBJ's are flipped (v -> 1 - v), as
  SeeSharp's ObjConverter does; they are written only for meshes whose material has a texture.
  Indices are 16-bit where a mesh has at most 65535 vertices. A missing normal attribute stays
  missing (flat shading, as in SeeSharp); a zero-length normal is replaced by the face normal.
  Zero-area triangles are dropped (neither renderer can hit or sample them).
* Textures are downscaled to at most 512 px on their longer side and stored as JPEG (quality 85)
  so that each scene stays a few MB. glTF's default sampler (repeat, linear) is used; SeeSharp
  repeats too (ImageTexture.BorderHandling.Repeat) but looks up the nearest texel. Colours: glTF
  decodes a baseColorTexture with the sRGB curve, SeeSharp's image reader (SimpleImageIO,
  stbi_loadf) with a pure 2.2 gamma; the two agree within 2 % above an 8-bit value of 0.4 and
  part below it (gamma 2.2 gives 0.63x at 0.1, 0.35x at 0.05). So the texels are re-encoded
  (v -> srgb_encode(v^2.2), a 256-entry table, before downscaling) that glTF's sRGB decoding
  gives SeeSharp's linear values. Texture files missing from the source give grey 0.5.
"""
import json
import math
import os
import shutil
import struct
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
MAX_TEXTURE_SIDE = 512
JPEG_QUALITY = 85
SEESHARP_MIN_ALPHA = 0.001   # GenericMaterial.ComputeLocalParams
MIXTRACE_MIN_ALPHA = 0.002   # shaders/shared/constants.h, kMinAlpha

def srgb_encode(linear):
    return 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055


# 8-bit value read by SeeSharp as (v/255)^2.2 -> the 8-bit value glTF's sRGB decoding reads the same.
GAMMA22_TO_SRGB = [min(255, max(0, round(255 * srgb_encode((v / 255) ** 2.2)))) for v in range(256)]

try:
    from PIL import Image
except ImportError:  # textures are skipped, said once per texture
    Image = None


# ---------------------------------------------------------------------------------------------
# PLY reading (binary little-endian and ASCII; the subset these scenes use).

PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
    "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}
UV_NAMES = (("u", "v"), ("s", "t"), ("texture_u", "texture_v"), ("texture_s", "texture_t"))


def fan_triangulate(polygons):
    """Polygons (lists of vertex indices) -> (n, 3) triangles, fanned around the first vertex."""
    tris = []
    for p in polygons:
        for i in range(2, len(p)):
            tris.append((p[0], p[i - 1], p[i]))
    return np.array(tris, dtype=np.int64).reshape(-1, 3)


def read_ply(path):
    """Returns dict(pos (n,3) f4, nrm (n,3) or None, uv (n,2) or None, tri (m,3) int64)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise ValueError(path + ": not a PLY file")
    body = data.index(b"\n", end) + 1
    fmt = None
    elements = []  # (name, count, [(prop name, type) | (name, ("list", count type, item type))])
    for line in data[:end].decode("ascii").splitlines():
        w = line.split()
        if not w or w[0] in ("ply", "comment", "obj_info"):
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w[0] == "property":
            if w[1] == "list":
                elements[-1][2].append((w[4], ("list", PLY_TYPES[w[2]], PLY_TYPES[w[3]])))
            else:
                elements[-1][2].append((w[2], PLY_TYPES[w[1]]))
    if fmt not in ("binary_little_endian", "ascii"):
        raise ValueError(path + ": PLY format " + str(fmt) + " is not supported")

    vertex = None
    polygons = None
    if fmt == "ascii":
        tokens = data[body:].split()
        at = 0
        for name, count, props in elements:
            rows = []
            for _ in range(count):
                row = []
                for pname, ptype in props:
                    if isinstance(ptype, tuple):
                        n = int(tokens[at]); at += 1
                        row.append([int(t) for t in tokens[at:at + n]]); at += n
                    else:
                        row.append(float(tokens[at])); at += 1
                rows.append(row)
            if name == "vertex":
                vertex = {p[0]: np.array([r[i] for r in rows], dtype=np.float32) for i, p in enumerate(props)}
            elif name == "face":
                polygons = [r[0] for r in rows]
    else:
        at = body
        for name, count, props in elements:
            if all(not isinstance(t, tuple) for _, t in props):
                dt = np.dtype([(p, "<" + t) for p, t in props])
                arr = np.frombuffer(data, dtype=dt, count=count, offset=at)
                at += dt.itemsize * count
                if name == "vertex":
                    vertex = {p: arr[p].astype(np.float32) for p, _ in props}
                continue
            if len(props) != 1:
                raise ValueError(path + ": a list element with other properties is not supported")
            _, (_, ct, it) = props[0]
            # Fast path: every face a triangle (or every face a quad), checked, not assumed.
            polys = None
            for k in (3, 4):
                dt = np.dtype([("n", "<" + ct), ("i", "<" + it, (k,))])
                if at + dt.itemsize * count <= len(data):
                    arr = np.frombuffer(data, dtype=dt, count=count, offset=at)
                    if np.all(arr["n"] == k):
                        polys = arr["i"].astype(np.int64)
                        at += dt.itemsize * count
                        break
            if polys is None:  # mixed polygon sizes: one at a time
                csize, isize = np.dtype(ct).itemsize, np.dtype(it).itemsize
                polys = []
                for _ in range(count):
                    n = int(np.frombuffer(data, dtype="<" + ct, count=1, offset=at)[0]); at += csize
                    polys.append(np.frombuffer(data, dtype="<" + it, count=n, offset=at).astype(np.int64).tolist())
                    at += isize * n
            if name == "face":
                polygons = polys
    if vertex is None or polygons is None:
        raise ValueError(path + ": no vertex or face element")
    tri = polygons if isinstance(polygons, np.ndarray) and polygons.shape[1] == 3 else fan_triangulate(polygons)
    pos = np.stack([vertex["x"], vertex["y"], vertex["z"]], axis=1)
    nrm = np.stack([vertex["nx"], vertex["ny"], vertex["nz"]], axis=1) if "nx" in vertex else None
    uv = None
    for un, vn in UV_NAMES:
        if un in vertex and vn in vertex:
            uv = np.stack([vertex[un], vertex[vn]], axis=1)
            break
    return {"pos": pos, "nrm": nrm, "uv": uv, "tri": tri}


# ---------------------------------------------------------------------------------------------
# OBJ reading: one mesh per material (usemtl), vertices de-duplicated per (v, vt, vn) triple.


def read_obj(path):
    """Returns [(material name, mesh dict)]; texture v flipped to glTF's top-left origin."""
    v, vt, vn = [], [], []
    groups = {}  # material -> list of polygons of (vi, ti, ni)
    order = []
    current = None
    with open(path, "r", encoding="utf-8", errors="replace") as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                v.append([float(x) for x in w[1:4]])
            elif w[0] == "vt":
                vt.append([float(w[1]), float(w[2]) if len(w) > 2 else 0.0])
            elif w[0] == "vn":
                vn.append([float(x) for x in w[1:4]])
            elif w[0] == "usemtl":
                current = " ".join(w[1:])
            elif w[0] == "f":
                poly = []
                for c in w[1:]:
                    parts = (c.split("/") + ["", ""])[:3]
                    def ix(s, n):
                        if not s:
                            return -1
                        i = int(s)
                        return i - 1 if i > 0 else n + i
                    poly.append((ix(parts[0], len(v)), ix(parts[1], len(vt)), ix(parts[2], len(vn))))
                if current not in groups:
                    groups[current] = []
                    order.append(current)
                groups[current].append(poly)
    v, vt, vn = np.array(v, np.float32), np.array(vt, np.float32).reshape(-1, 2), np.array(vn, np.float32).reshape(-1, 3)
    result = []
    for material in order:
        polys = groups[material]
        has_n = all(c[2] >= 0 for p in polys for c in p)
        has_t = all(c[1] >= 0 for p in polys for c in p)
        remap = {}
        keys = []
        out_polys = []
        for p in polys:
            q = []
            for c in p:
                key = (c[0], c[1] if has_t else -1, c[2] if has_n else -1)
                if key not in remap:
                    remap[key] = len(keys)
                    keys.append(key)
                q.append(remap[key])
            out_polys.append(q)
        k = np.array(keys, dtype=np.int64)
        uv = None
        if has_t:
            uv = vt[k[:, 1]].copy()
            uv[:, 1] = 1.0 - uv[:, 1]
        result.append((material, {"pos": v[k[:, 0]], "nrm": vn[k[:, 2]] if has_n else None, "uv": uv,
                                  "tri": fan_triangulate(out_polys)}))
    return result


# ---------------------------------------------------------------------------------------------
# SeeSharp conventions: transforms, materials, emitters.


def rot_x(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def seesharp_transform(t):
    """A named transform -> 4x4 column-vector matrix (see the header for the convention)."""
    if "matrix" in t:
        # System.Numerics rows: M11..M14, ..., M41..M44; row-vector convention, so the
        # column-vector matrix is its transpose.
        return np.array(t["matrix"], dtype=np.float64).reshape(4, 4).T
    m = np.eye(4)
    s = t.get("scale", [1, 1, 1])
    r = [math.radians(a) for a in t.get("rotation", [0, 0, 0])]
    p = t.get("position", [0, 0, 0])
    m[:3, :3] = rot_y(r[1]) @ rot_x(r[0]) @ rot_z(r[2]) @ np.diag(s)
    m[:3, 3] = p
    return m


def rgb(value):
    if isinstance(value, dict):
        return [float(x) for x in value["value"]]
    return [float(x) for x in value]


class Notes:
    """What the conversion changed or dropped, printed and written to the scene's README."""

    def __init__(self):
        self.lines = []

    def add(self, text):
        if text not in self.lines:
            self.lines.append(text)
            print("  note: " + text)


# ---------------------------------------------------------------------------------------------
# glTF writing.


class GltfWriter:
    def __init__(self):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "mixtrace scenes/paper/convert_seesharp.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                    "accessors": [], "bufferViews": [], "buffers": []}

    def view(self, payload, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        bv = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(payload)}
        if target:
            bv["target"] = target
        self.bin += payload
        self.doc["bufferViews"].append(bv)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, arr, kind, target, minmax=False):
        arr = np.ascontiguousarray(arr)
        comp = {np.dtype(np.float32): 5126, np.dtype(np.uint32): 5125, np.dtype(np.uint16): 5123}[arr.dtype]
        acc = {"bufferView": self.view(arr.tobytes(), target), "componentType": comp,
               "count": int(arr.shape[0]), "type": kind}
        if minmax:
            acc["min"] = [float(x) for x in arr.min(axis=0)]
            acc["max"] = [float(x) for x in arr.max(axis=0)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def node(self, entry):
        self.doc["nodes"].append(entry)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)


def load_texture(src_dir, filename, notes):
    """A texture file -> (JPEG bytes, mean colour) or (None, None) when it cannot be used."""
    path = os.path.join(src_dir, filename)
    if not os.path.exists(path):
        notes.add("texture %s is missing from the source; grey 0.5 instead" % filename)
        return None, None
    if Image is None:
        notes.add("PIL is not available: texture %s skipped; grey 0.5 instead" % filename)
        return None, None
    import io
    img = Image.open(path).convert("RGB").point(GAMMA22_TO_SRGB * 3)
    scale = MAX_TEXTURE_SIDE / max(img.size)
    if scale < 1:
        img = img.resize((max(1, round(img.size[0] * scale)), max(1, round(img.size[1] * scale))), Image.LANCZOS)
    out = io.BytesIO()
    img.save(out, format="JPEG", quality=JPEG_QUALITY, optimize=True)
    return out.getvalue(), None


def convert_material(w, src_dir, m, textures, notes):
    """A SeeSharp material (JSON) -> index of a glTF material; emissive ones are one-sided."""
    name = m["name"]
    kind = m.get("type", "generic")
    pbr = {"metallicFactor": 0.0, "roughnessFactor": 1.0}
    base = m.get("baseColor", {"type": "rgb", "value": [1, 1, 1]})
    if isinstance(base, dict) and base.get("type") == "image":
        fn = base["filename"]
        if fn not in textures:
            data, _ = load_texture(src_dir, fn, notes)
            textures[fn] = None
            if data is not None:
                bv = w.view(data)
                w.doc.setdefault("images", []).append({"bufferView": bv, "mimeType": "image/jpeg", "name": fn})
                w.doc.setdefault("textures", []).append({"source": len(w.doc["images"]) - 1})
                textures[fn] = len(w.doc["textures"]) - 1
        if textures[fn] is None:
            pbr["baseColorFactor"] = [0.5, 0.5, 0.5, 1.0]
        else:
            pbr["baseColorTexture"] = {"index": textures[fn]}
    else:
        pbr["baseColorFactor"] = [min(max(c, 0.0), 1.0) for c in rgb(base)] + [1.0]
    if kind == "generic":
        pbr["metallicFactor"] = float(m.get("metallic", 0.0))
        rough = m.get("roughness", 0.5)
        if isinstance(rough, dict):
            notes.add("material %s: roughness texture dropped, 0.5 instead" % name)
            rough = 0.5
        pbr["roughnessFactor"] = float(rough)
        if float(rough) ** 2 < MIXTRACE_MIN_ALPHA:
            notes.add("material %s: roughness %g renders as %.3f here (GGX alpha clamp %g; SeeSharp's %g)"
                      % (name, float(rough), math.sqrt(MIXTRACE_MIN_ALPHA), MIXTRACE_MIN_ALPHA, SEESHARP_MIN_ALPHA))
        if float(m.get("specularTransmittance", 0.0)) > 0:
            notes.add("material %s: specularTransmittance %g dropped (opaque here)" % (name, m["specularTransmittance"]))
        if float(m.get("diffuseTransmittance", 0.0)) > 0:
            notes.add("material %s: diffuseTransmittance dropped" % name)
    elif kind != "diffuse":
        raise ValueError("material %s: unknown type %s" % (name, kind))
    if m.get("emissionIsGlossy", False):
        raise ValueError("material %s: glossy emitters are not supported" % name)
    out = {"name": name, "pbrMetallicRoughness": pbr, "doubleSided": True}
    emission = rgb(m["emission"]) if "emission" in m and m["emission"] is not None else [0, 0, 0]
    if max(emission) > 0:
        set_emission(out, emission)
    w.doc["materials"].append(out)
    return len(w.doc["materials"]) - 1


def set_emission(material, emission):
    peak = max(emission)
    material["doubleSided"] = False  # SeeSharp's emitters are one-sided
    material["emissiveFactor"] = [e / peak if peak > 1 else e for e in emission]
    if peak > 1:
        material["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": peak}}


def orient_emitter(mesh):
    """Flips the winding of every triangle whose geometric normal disagrees with its shading
    normals (SeeSharp emits on the shading normal's side, mixtrace on the winding's). Returns
    the number flipped."""
    if mesh["nrm"] is None:
        return 0  # SeeSharp uses the face normal: the winding already decides
    p, n, t = mesh["pos"].astype(np.float64), mesh["nrm"].astype(np.float64), mesh["tri"]
    ng = np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]])
    ns = n[t[:, 0]] + n[t[:, 1]] + n[t[:, 2]]
    bad = np.einsum("ij,ij->i", ng, ns) < 0
    t[bad] = t[bad][:, [0, 2, 1]]
    return int(bad.sum())


def fix_normals(mesh):
    """Normalises NORMAL; a zero or non-finite one becomes the normal of a face using it."""
    if mesh["nrm"] is None:
        return
    n = mesh["nrm"].astype(np.float64)
    length = np.linalg.norm(n, axis=1)
    bad = ~(length > 1e-12) | ~np.isfinite(length)
    if bad.any():
        p, t = mesh["pos"].astype(np.float64), mesh["tri"]
        fn = np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]])
        acc = np.zeros_like(n)
        for k in range(3):
            np.add.at(acc, t[:, k], fn)
        n[bad] = acc[bad]
        length = np.linalg.norm(n, axis=1)
        n[~(length > 0)] = [0, 1, 0]
        length = np.linalg.norm(n, axis=1)
    mesh["nrm"] = (n / length[:, None]).astype(np.float32)


def drop_degenerate(mesh):
    """Removes zero-area triangles (repeated vertices, collinear corners): they are invisible to
    both renderers, and mixtrace's loader would drop them with a warning. Returns how many."""
    p, t = mesh["pos"].astype(np.float32).astype(np.float64), mesh["tri"]
    area2 = np.linalg.norm(np.cross(p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]), axis=1)
    keep = area2 > 0
    mesh["tri"] = t[keep]
    return int((~keep).sum())


def add_mesh(w, name, mesh, material):
    attrs = {"POSITION": w.accessor(mesh["pos"].astype(np.float32), "VEC3", 34962, minmax=True)}
    if mesh["nrm"] is not None:
        attrs["NORMAL"] = w.accessor(mesh["nrm"], "VEC3", 34962)
    textured = "baseColorTexture" in w.doc["materials"][material]["pbrMetallicRoughness"]
    if mesh["uv"] is not None and textured:  # UVs only where a texture reads them: smaller files
        attrs["TEXCOORD_0"] = w.accessor(mesh["uv"].astype(np.float32), "VEC2", 34962)
    # 16-bit indices where the vertices fit: half the index bytes (glTF core allows both).
    index_type = np.uint16 if len(mesh["pos"]) <= 65535 else np.uint32
    idx = w.accessor(mesh["tri"].astype(index_type).reshape(-1), "SCALAR", 34963)
    w.doc["meshes"].append({"name": name, "primitives": [{"attributes": attrs, "indices": idx, "material": material}]})
    w.node({"name": name, "mesh": len(w.doc["meshes"]) - 1})


def convert(src_dir, out_root):
    scene_name = os.path.basename(os.path.normpath(src_dir))
    with open(os.path.join(src_dir, scene_name + ".json"), "r", encoding="utf-8") as f:
        js = json.load(f)
    print(scene_name)
    notes = Notes()
    w = GltfWriter()
    if "background" in js:
        notes.add("background (environment map %s) dropped: mixtrace has no environment lighting"
                  % js["background"].get("filename", "?"))

    transforms = {t["name"]: seesharp_transform(t) for t in js["transforms"]}
    cam = js["cameras"][-1]  # SeeSharp keeps the last camera
    w.doc["cameras"] = [{"type": "perspective", "name": cam["name"],
                         "perspective": {"yfov": math.radians(float(cam["fov"])), "znear": 0.001, "zfar": 1000.0}}]
    w.node({"name": "camera", "camera": 0, "matrix": [float(x) for x in transforms[cam["transform"]].T.reshape(-1)]})

    textures = {}
    materials = {}
    json_materials = {m["name"]: m for m in js["materials"]}

    def material_index(name):
        if name not in materials:
            materials[name] = convert_material(w, src_dir, json_materials[name], textures, notes)
        return materials[name]

    triangles = emissive = flipped = degenerate = 0
    for obj in js["objects"]:
        path = os.path.join(src_dir, obj["relativePath"])
        if not os.path.exists(path):
            notes.add("mesh %s is missing from the source; left out" % obj["relativePath"])
            continue
        if obj["type"] == "ply":
            parts = [(obj["material"], read_ply(path))]
        elif obj["type"] == "obj":
            parts = read_obj(path)
        else:
            raise ValueError("object %s: unknown type %s" % (obj["name"], obj["type"]))
        for material_name, mesh in parts:
            if material_name not in json_materials:
                notes.add("OBJ material %s has no JSON definition; SeeSharp's default (white diffuse)" % material_name)
                json_materials[material_name] = {"name": material_name, "type": "diffuse", "baseColor": [1, 1, 1]}
            mat = material_index(material_name)
            if "emission" in obj and max(rgb(obj["emission"])) > 0:
                # Object-level emission: a one-sided copy of the material for this object.
                copy = json.loads(json.dumps(w.doc["materials"][mat]))
                copy["name"] = material_name + " (" + obj["name"] + " emitter)"
                set_emission(copy, rgb(obj["emission"]))
                w.doc["materials"].append(copy)
                mat = len(w.doc["materials"]) - 1
            fix_normals(mesh)
            degenerate += drop_degenerate(mesh)
            n_tri = len(mesh["tri"])
            triangles += n_tri
            if "emissiveFactor" in w.doc["materials"][mat]:
                emissive += n_tri
                flipped += orient_emitter(mesh)
            add_mesh(w, obj["name"] if len(parts) == 1 else obj["name"] + "/" + material_name, mesh, mat)
    if degenerate:
        notes.add("%d zero-area triangles dropped" % degenerate)
    if flipped:
        notes.add("%d emissive triangles had a winding against their normals; flipped" % flipped)

    if any("extensions" in m for m in w.doc["materials"]):
        w.doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    for key in [k for k, v in w.doc.items() if v == []]:
        del w.doc[key]
    out_dir = os.path.join(out_root, scene_name)
    os.makedirs(out_dir, exist_ok=True)
    w.doc["buffers"] = [{"uri": scene_name + ".bin", "byteLength": len(w.bin)}]
    with open(os.path.join(out_dir, scene_name + ".bin"), "wb") as f:
        f.write(w.bin)
    with open(os.path.join(out_dir, scene_name + ".gltf"), "w", encoding="utf-8") as f:
        json.dump(w.doc, f, indent=1)
        f.write("\n")
    shutil.copyfile(os.path.join(src_dir, "LICENSE.txt"), os.path.join(out_dir, "LICENSE.txt"))
    with open(os.path.join(out_dir, "NOTES.txt"), "w", encoding="utf-8") as f:
        f.write("%s, converted by scenes/paper/convert_seesharp.py from github.com/qingqhua/"
                "ControlledMixtureSampling Scenes/%s (licence: LICENSE.txt).\n" % (scene_name, scene_name))
        f.write("%d triangles, %d emissive.\n" % (triangles, emissive))
        for line in notes.lines:
            f.write("- " + line + "\n")
    print("  %d triangles, %d emissive, %.2f MB" % (triangles, emissive, len(w.bin) / 1e6))


# ---------------------------------------------------------------------------------------------
# --check: the shipped files parse, their accessors are in range, emitters are one-sided and
# wound with their normals. Written against the glTF spec, not against the writer above.

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
COMPONENT_TYPES = {5126: np.float32, 5125: np.uint32, 5123: np.uint16, 5121: np.uint8}


def read_accessor(doc, buf, index):
    acc = doc["accessors"][index]
    bv = doc["bufferViews"][acc["bufferView"]]
    dt = np.dtype(COMPONENT_TYPES[acc["componentType"]])
    n = COMPONENTS[acc["type"]]
    stride = bv.get("byteStride", dt.itemsize * n)
    start = bv.get("byteOffset", 0) + acc.get("byteOffset", 0)
    need = stride * (acc["count"] - 1) + dt.itemsize * n if acc["count"] else 0
    assert bv.get("byteOffset", 0) + bv["byteLength"] <= len(buf), "bufferView outside the buffer"
    assert acc.get("byteOffset", 0) + need <= bv["byteLength"], "accessor %d outside its bufferView" % index
    assert stride == dt.itemsize * n, "interleaved accessors are not written by the converter"
    return np.frombuffer(buf, dtype=dt, count=acc["count"] * n, offset=start).reshape(acc["count"], n)


def check_scene(gltf_path):
    with open(gltf_path, "r", encoding="utf-8") as f:
        doc = json.load(f)
    with open(os.path.join(os.path.dirname(gltf_path), doc["buffers"][0]["uri"]), "rb") as f:
        buf = f.read()
    assert len(buf) >= doc["buffers"][0]["byteLength"], "buffer shorter than declared"
    assert len(doc.get("cameras", [])) == 1, "exactly one camera"
    triangles = emissive = 0
    for mesh in doc["meshes"]:
        for prim in mesh["primitives"]:
            pos = read_accessor(doc, buf, prim["attributes"]["POSITION"]).astype(np.float64)
            acc = doc["accessors"][prim["attributes"]["POSITION"]]
            assert np.allclose(pos.min(axis=0), acc["min"]) and np.allclose(pos.max(axis=0), acc["max"]), \
                mesh["name"] + ": POSITION min/max wrong"
            assert np.all(np.isfinite(pos)), mesh["name"] + ": non-finite position"
            for attr in ("NORMAL", "TEXCOORD_0"):
                if attr in prim["attributes"]:
                    a = read_accessor(doc, buf, prim["attributes"][attr])
                    assert len(a) == len(pos) and np.all(np.isfinite(a)), mesh["name"] + ": bad " + attr
            idx = read_accessor(doc, buf, prim["indices"]).reshape(-1, 3).astype(np.int64)
            assert idx.size == 0 or idx.max() < len(pos), mesh["name"] + ": index out of range"
            triangles += len(idx)
            mat = doc["materials"][prim["material"]]
            strength = mat.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
            if max(mat.get("emissiveFactor", [0, 0, 0])) * strength > 0:
                emissive += len(idx)
                assert mat.get("doubleSided", False) is False, mat["name"] + ": an emitter must be one-sided"
                if "NORMAL" in prim["attributes"]:
                    n = read_accessor(doc, buf, prim["attributes"]["NORMAL"]).astype(np.float64)
                    ng = np.cross(pos[idx[:, 1]] - pos[idx[:, 0]], pos[idx[:, 2]] - pos[idx[:, 0]])
                    ns = n[idx[:, 0]] + n[idx[:, 1]] + n[idx[:, 2]]
                    wrong = int((np.einsum("ij,ij->i", ng, ns) < 0).sum())
                    assert wrong == 0, "%s: %d emissive triangles wound against their normals" % (mesh["name"], wrong)
    assert emissive > 0, "no emitters"
    for img in doc.get("images", []):
        bv = doc["bufferViews"][img["bufferView"]]
        head = buf[bv.get("byteOffset", 0):bv.get("byteOffset", 0) + 3]
        assert head == b"\xff\xd8\xff", img.get("name", "?") + ": not a JPEG"
        if Image is not None:
            import io
            im = Image.open(io.BytesIO(buf[bv.get("byteOffset", 0):bv.get("byteOffset", 0) + bv["byteLength"]]))
            assert max(im.size) <= MAX_TEXTURE_SIDE, img.get("name", "?") + ": larger than the limit"
    size = os.path.getsize(gltf_path) + len(buf)
    print("%s: %d triangles, %d emissive, %.2f MB: ok" % (os.path.basename(gltf_path), triangles, emissive, size / 1e6))
    return triangles


def check_ply_reader():
    """The PLY reader on a quad and a triangle written both ways: ASCII and binary little-endian
    must read the same, polygons fanned (0 1 2, 0 2 3) as SeeSharp triangulates them."""
    import tempfile
    verts = [(0, 0, 0, 0, 0, 1, 0, 0), (1, 0, 0, 0, 0, 1, 1, 0), (1, 1, 0, 0, 0, 1, 1, 1), (0, 1, 0, 0, 0, 1, 0, 1)]
    faces = [(0, 1, 2, 3), (0, 2, 3)]
    header = ("ply\nformat %s 1.0\nelement vertex 4\n" + "".join("property float %s\n" % n for n in
              ("x", "y", "z", "nx", "ny", "nz", "s", "t")) +
              "element face 2\nproperty list uchar uint vertex_indices\nend_header\n")
    ascii_body = "".join(" ".join("%g" % x for x in v) + "\n" for v in verts) + \
        "".join("%d %s\n" % (len(f), " ".join(map(str, f))) for f in faces)
    binary_body = b"".join(struct.pack("<8f", *v) for v in verts) + \
        b"".join(struct.pack("<B%dI" % len(f), len(f), *f) for f in faces)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for fmt, body in (("ascii", ascii_body.encode()), ("binary_little_endian", binary_body)):
            path = os.path.join(tmp, fmt + ".ply")
            with open(path, "wb") as f:
                f.write((header % fmt).encode() + body)
            results.append(read_ply(path))
    for r in results:
        assert r["tri"].tolist() == [[0, 1, 2], [0, 2, 3], [0, 2, 3]], "PLY faces: %s" % r["tri"].tolist()
        assert np.allclose(r["pos"], [v[:3] for v in verts]) and np.allclose(r["uv"], [v[6:] for v in verts])
        assert np.allclose(r["nrm"], [v[3:6] for v in verts])
    print("PLY reader (ascii, binary_little_endian): ok")


def check_all(root=HERE):
    check_ply_reader()
    scenes = sorted(d for d in os.listdir(root) if os.path.isfile(os.path.join(root, d, d + ".gltf")))
    if not scenes:
        print("no converted scenes found under " + root)
        return 1
    failed = 0
    for d in scenes:
        try:
            check_scene(os.path.join(root, d, d + ".gltf"))
            assert os.path.isfile(os.path.join(root, d, "LICENSE.txt")), d + ": LICENSE.txt missing"
        except (AssertionError, KeyError, ValueError) as e:
            print("%s: FAILED: %s" % (d, e))
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) in (2, 3) and sys.argv[1] == "--check":  # optional: another folder of scenes
        sys.exit(check_all(*sys.argv[2:]))
    if len(sys.argv) < 2 or sys.argv[1].startswith("-"):
        print(__doc__)
        sys.exit(2)
    for src in sys.argv[1:]:
        convert(src, HERE)
