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
NOTES.txt. DiningRoom2's environment map (its JSON's "background") is written beside it as
Skydome.exr in mixtrace's convention (below): render it with `--env Skydome.exr`.
GlossyManyLights is not one of the paper's table scenes and is not shipped.

Conventions followed (read from SeeSharp's loader, GitHub pgrit/SeeSharp: SeeSharp/IO/JsonScene.cs,
PlyFile.cs, ObjConverter.cs, Cameras/PerspectiveCamera.cs, Shading/Materials/GenericMaterial.cs,
Shading/Emitters/DiffuseEmitter.cs, Shading/Background/EnvironmentMap.cs; the reference
implementation builds on SeeSharp 1.9.0, whose files these are read from where they differ):

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
* The environment map (a "background" of type "image"; SeeSharp 1.9.0's JsonScene.ReadBackground
  reads its filename only: no scale, no rotation, so --env-scale 1 and --env-rotate 0). SeeSharp's
  EnvironmentMap looks a direction d up as phi = atan2(d.z, d.x) wrapped to [0, 2 pi),
  theta = atan2(sqrt(d.x^2 + d.z^2), d.y), texel (column, row) = (int(phi / 2 pi * W),
  int(theta / pi * H)), row 0 the image's top as SimpleImageIO holds it (its PFM reader,
  Core/imageio.cpp CachePfmImage, reverses the file's bottom-to-top rows, as mixtrace's does).
  So +Y is the top row, +X column 0, +Z column W/4, -X W/2, -Z 3W/4: SeeSharp's own test
  (SeeSharp.Tests Background_EnvironmentMap.Rotation_ShouldBeCW: texel (0, H/2) is +X, (W/4, H/2)
  is +Z) says the same, and the class comment's "longitude zero is -X" does not match its code.
  mixtrace's map (docs/conventions.md, shaders/shared/environment.h; Mitsuba 3's envmap) has
  u = atan2(d.x, -d.z) / 2 pi and v = acos(d.y) / pi: -Z column 0, +X W/4, +Z W/2, -X 3W/4, the
  same rows. Both longitudes turn the same way (+X towards +Z), a quarter turn apart:
  u_mixtrace = u_SeeSharp + 1/4. So the image is rolled by W/4 columns to the right (SeeSharp's
  column c becomes column (c + W/4) mod W), unflipped and unresampled: every direction reads the
  texel SeeSharp reads, nearest texel in both renderers. It is written as a 32-bit float
  OpenEXR (ZIP compression: lossless; DiningRoom2's 512x256 Skydome.pfm of 1.57 MB becomes
  0.73 MB), named after the source file.
"""
import json
import math
import os
import shutil
import struct
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPOSITORY = os.path.dirname(os.path.dirname(HERE))
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
# The environment map: SeeSharp's equirectangular map -> mixtrace's (see the header), as OpenEXR.


def read_pfm(path):
    """A PFM file (PF colour or Pf grey) -> (H, W, 3) float32, row 0 the image's top (PFM stores
    rows bottom to top; SeeSharp's reader and mixtrace's both reverse them)."""
    with open(path, "rb") as f:
        data = f.read()
    fields, at = [], 0
    while len(fields) < 4:  # "PF", width, height, scale: whitespace-separated, one byte after the last
        while data[at:at + 1].isspace():
            at += 1
        end = at
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[at:end].decode("ascii"))
        at = end
    at += 1
    channels = {"PF": 3, "Pf": 1}[fields[0]]
    w, h, scale = int(fields[1]), int(fields[2]), float(fields[3])
    img = np.frombuffer(data, dtype="<f4" if scale < 0 else ">f4", count=w * h * channels, offset=at)
    img = img.reshape(h, w, channels)[::-1].astype(np.float32)
    return np.repeat(img, 3, axis=2) if channels == 1 else img


def seesharp_env_to_mixtrace(img):
    """SeeSharp's map (H, W, 3), top row first -> mixtrace's: rolled W/4 columns to the right."""
    w = img.shape[1]
    if w % 4:
        raise ValueError("an environment map %d texels wide: a quarter turn is not a whole number of columns" % w)
    return np.roll(img, w // 4, axis=1)


EXR_MAGIC = 20000630
EXR_ZIP_LINES = 16  # ZIP_COMPRESSION: 16 scanlines per chunk


def _exr_attr(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def write_exr(path, img):
    """(H, W, 3) float32 -> a scanline OpenEXR of FLOAT channels B, G, R, ZIP-compressed
    (lossless), row 0 the top (INCREASING_Y). The same bytes on every run."""
    import zlib
    h, w, _ = img.shape
    chlist = b"".join(c + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    box = struct.pack("<4i", 0, 0, w - 1, h - 1)
    header = struct.pack("<ii", EXR_MAGIC, 2) + b"".join([
        _exr_attr("channels", "chlist", chlist), _exr_attr("compression", "compression", b"\x03"),
        _exr_attr("dataWindow", "box2i", box), _exr_attr("displayWindow", "box2i", box),
        _exr_attr("lineOrder", "lineOrder", b"\x00"), _exr_attr("pixelAspectRatio", "float", struct.pack("<f", 1)),
        _exr_attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0)),
        _exr_attr("screenWindowWidth", "float", struct.pack("<f", 1))]) + b"\0"
    planar = np.ascontiguousarray(img[:, :, ::-1].transpose(0, 2, 1).astype("<f4"))  # per row: B..., G..., R...
    chunks = []
    for y in range(0, h, EXR_ZIP_LINES):
        raw = np.frombuffer(planar[y:y + EXR_ZIP_LINES].tobytes(), dtype=np.uint8)
        t = np.concatenate([raw[0::2], raw[1::2]])  # OpenEXR's ZIP: bytes reordered, then deltas
        d = t.copy()
        d[1:] = (t[1:].astype(np.int16) - t[:-1] + 128) & 0xFF
        packed = zlib.compress(d.tobytes(), 9)
        if len(packed) >= len(raw):
            packed = raw.tobytes()  # stored uncompressed where compressing does not pay
        chunks.append(struct.pack("<ii", y, len(packed)) + packed)
    offsets, at = [], len(header) + 8 * len(chunks)
    for c in chunks:
        offsets.append(at)
        at += len(c)
    with open(path, "wb") as f:
        f.write(header + struct.pack("<%dQ" % len(offsets), *offsets) + b"".join(chunks))


def read_exr(path):
    """Reads back what write_exr writes (scanline, FLOAT R, G, B, no or ZIP compression) ->
    (H, W, 3) float32, row 0 the top. Written against the OpenEXR file layout, for --check."""
    import zlib
    with open(path, "rb") as f:
        data = f.read()
    magic, version = struct.unpack_from("<ii", data, 0)
    assert magic == EXR_MAGIC and version & 0xFF == 2 and not version & 0x1E00, "not a single-part scanline EXR"
    at, attrs = 8, {}
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        kind_end = data.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", data, kind_end + 1)[0]
        attrs[data[at:name_end].decode()] = data[kind_end + 5:kind_end + 5 + size]
        at = kind_end + 5 + size
    at += 1
    channels, c = [], 0
    chl = attrs["channels"]
    while chl[c] != 0:
        end = chl.index(b"\0", c)
        ptype, _, xs, ys = struct.unpack_from("<iB3xii", chl, end + 1)
        assert ptype == 2 and xs == 1 and ys == 1, "channels must be FLOAT, unsampled"
        channels.append(chl[c:end].decode())
        c = end + 17
    assert sorted(channels) == ["B", "G", "R"], "channels %s, not R, G, B" % channels
    compression = attrs["compression"][0]
    assert compression in (0, 3), "compression %d (only none and ZIP are read)" % compression
    lines = {0: 1, 3: EXR_ZIP_LINES}[compression]
    x0, y0, x1, y1 = struct.unpack("<4i", attrs["dataWindow"])
    w, h = x1 - x0 + 1, y1 - y0 + 1
    n = (h + lines - 1) // lines
    planar = np.zeros((h, len(channels), w), dtype="<f4")
    for k, offset in enumerate(struct.unpack_from("<%dQ" % n, data, at)):
        y, size = struct.unpack_from("<ii", data, offset)
        rows = min(lines, y1 + 1 - y)
        payload = data[offset + 8:offset + 8 + size]
        expected = rows * len(channels) * w * 4
        if size < expected:
            d = np.frombuffer(zlib.decompress(payload), dtype=np.uint8).astype(np.int64)
            t = ((np.cumsum(d - 128) + 128) & 0xFF).astype(np.uint8)
            t[0] = d[0]
            raw = np.empty_like(t)
            half = (len(t) + 1) // 2
            raw[0::2], raw[1::2] = t[:half], t[half:]
            payload = raw.tobytes()
        assert len(payload) == expected, "chunk %d: %d bytes, not %d" % (k, len(payload), expected)
        planar[y - y0:y - y0 + rows] = np.frombuffer(payload, dtype="<f4").reshape(rows, len(channels), w)
    order = [channels.index(ch) for ch in ("R", "G", "B")]
    return planar[:, order, :].transpose(0, 2, 1).astype(np.float32)


def convert_background(src_dir, background, out_dir, notes):
    """Writes the scene's environment map in mixtrace's convention; returns its file name."""
    if background.get("type") != "image":
        raise ValueError("background of type %s is not supported" % background.get("type"))
    unknown = sorted(set(background) - {"type", "filename"})
    if unknown:  # SeeSharp 1.9.0 reads none: a newer field would need its meaning worked out
        raise ValueError("background fields %s are not understood" % unknown)
    src = background["filename"]
    if not src.lower().endswith(".pfm"):
        raise ValueError("background %s: only PFM environment maps are converted" % src)
    img = seesharp_env_to_mixtrace(read_pfm(os.path.join(src_dir, src)))
    name = os.path.splitext(os.path.basename(src))[0] + ".exr"
    os.makedirs(out_dir, exist_ok=True)
    write_exr(os.path.join(out_dir, name), img)
    notes.add("environment map %s (%dx%d) written as %s in mixtrace's convention (columns rolled by a quarter "
              "turn, texels unchanged); scale 1, no rotation (the JSON gives none)"
              % (src, img.shape[1], img.shape[0], name))
    return name


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
    out_dir = os.path.join(out_root, scene_name)
    environment = convert_background(src_dir, js["background"], out_dir, notes) if "background" in js else None

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
        if environment:
            rel = lambda name: os.path.relpath(os.path.join(out_dir, name), REPOSITORY).replace(os.sep, "/")
            f.write("Render it with its environment light:\n    build/mixtrace render %s --env %s\n"
                    % (rel(scene_name + ".gltf"), rel(environment)))
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


def check_environment_conversion():
    """The quarter-turn roll against the two renderers' lookups, written out from their sources:
    for many directions, SeeSharp's texel of a random map and mixtrace's texel of the converted
    map are the same texel. And write_exr / read_exr give back the exact floats."""
    rng = np.random.default_rng(7)
    h, w = 8, 16
    seesharp = rng.random((h, w, 3)).astype(np.float32)
    ours = seesharp_env_to_mixtrace(seesharp)
    d = rng.normal(size=(4000, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    # SeeSharp 1.9.0, EnvironmentMap.WorldToSpherical / SphericalToPixel / EmittedRadiance.
    phi = np.arctan2(d[:, 2], d[:, 0])
    phi = np.where(phi < 0, phi + 2 * math.pi, phi)
    theta = np.arctan2(np.sqrt(d[:, 0] ** 2 + d[:, 2] ** 2), d[:, 1])
    s_col, s_row = phi / (2 * math.pi) * w, theta / math.pi * h
    # mixtrace, shaders/shared/environment.h: u = atan2(x, -z) / 2 pi wrapped to [0, 1), v = acos(y) / pi.
    u = np.arctan2(d[:, 0], -d[:, 2]) / (2 * math.pi)
    u = u - np.floor(u)
    m_col, m_row = u * w, np.arccos(np.clip(d[:, 1], -1, 1)) / math.pi * h
    clear = (np.abs(s_col - np.round(s_col)) > 1e-6) & (np.abs(s_row - np.round(s_row)) > 1e-6)
    a = seesharp[s_row.astype(int)[clear], s_col.astype(int)[clear]]
    b = ours[m_row.astype(int)[clear] % h, m_col.astype(int)[clear] % w]
    assert np.array_equal(a, b), "%d of %d directions read another texel" % ((a != b).any(axis=1).sum(), len(a))
    # +X and +Z, as SeeSharp's own test places them: column 0 and W/4 there, W/4 and W/2 here.
    assert np.array_equal(ours[h // 2, w // 4], seesharp[h // 2, 0])
    assert np.array_equal(ours[h // 2, w // 2], seesharp[h // 2, w // 4])
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        for img in (seesharp, np.zeros((40, 80, 3), np.float32),  # random: stored raw; zeros: compressed
                    np.repeat(np.linspace(0, 5, 33 * 66, dtype=np.float32).reshape(33, 66, 1), 3, axis=2)):
            path = os.path.join(tmp, "e.exr")
            write_exr(path, img)
            assert np.array_equal(read_exr(path), img), "EXR round trip of a %dx%d map" % img.shape[1::-1]
    print("environment map: quarter-turn roll (%d directions), EXR round trip: ok" % clear.sum())


def check_environment(scene_dir):
    """An environment map named by the scene's NOTES.txt (`--env FILE`) exists and is a sane
    equirectangular map of radiance: 2:1, finite, non-negative, not black."""
    notes_path = os.path.join(scene_dir, "NOTES.txt")
    if not os.path.isfile(notes_path):
        return
    with open(notes_path, "r", encoding="utf-8") as f:
        named = [w for line in f for k, w in zip(line.split(), line.split()[1:]) if k == "--env"]
    for name in named:
        path = os.path.join(REPOSITORY, name)
        assert os.path.isfile(path), "NOTES.txt names --env %s, which does not exist" % name
        img = read_exr(path)
        h, w, _ = img.shape
        assert w == 2 * h, "%s: %dx%d is not an equirectangular map (2:1)" % (name, w, h)
        assert np.all(np.isfinite(img)) and img.min() >= 0 and img.max() > 0, name + ": not finite, negative or black"
        size = os.path.getsize(path)
        assert size <= 1.5e6, "%s: %.2f MB" % (name, size / 1e6)
        print("%s: %dx%d, mean radiance %.3f, %.2f MB: ok" % (name, w, h, img.mean(), size / 1e6))


def check_all(root=HERE):
    check_ply_reader()
    check_environment_conversion()
    scenes = sorted(d for d in os.listdir(root) if os.path.isfile(os.path.join(root, d, d + ".gltf")))
    if not scenes:
        print("no converted scenes found under " + root)
        return 1
    failed = 0
    for d in scenes:
        try:
            check_scene(os.path.join(root, d, d + ".gltf"))
            assert os.path.isfile(os.path.join(root, d, "LICENSE.txt")), d + ": LICENSE.txt missing"
            check_environment(os.path.join(root, d))
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
