#!/usr/bin/env python3
"""Checks mixtrace's glass (KHR_materials_transmission + _ior + _volume, shaders/shared/dielectric.h)
against Mitsuba 3's `dielectric` and `roughdielectric` (GGX, visible-normal sampling): the same
smooth-shaded icosphere of glass in front of the same environment map of coloured blocks (whose
convention both renderers share: mitsuba_envmap_convention.py), seen by the same camera, must give
the same image: where the refracted blocks land, how bright (Fresnel, 1/eta^2 in and out), how
blurred (roughness).

Conventions made equal: glTF roughness r is Mitsuba's alpha = r^2; mixtrace's smooth glass is GGX
at alpha 0.002 against Mitsuba's delta `dielectric`; a box pixel filter; square images (so the
field of view's axis does not matter); no Russian roulette; the same depth (mixtrace's
--max-depth counts ray segments from the camera, Mitsuba's max_depth too).

Needs Mitsuba 3 from the Python package registry (not a Debian package, so not part of the test
suite):  python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy
Run:     /tmp/mi/bin/python benchmarks/outside/mitsuba_glass.py build/mixtrace
Prints, per case, the mean of each image and the largest difference of 8x8-pixel block means
relative to the image's mean; exits 1 when one exceeds 5 %. Last run: docs/conventions.md (Glass).
"""
import base64, json, os, subprocess, sys, tempfile
import numpy as np
import mitsuba as mi

BINARY = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'build/mixtrace')
os.chdir(tempfile.mkdtemp(prefix='mixtrace-glass-'))
mi.set_variant('scalar_rgb')
SIZE, SPP, DEPTH = 64, 512, 12

# An environment of coloured blocks (22.5 degrees on a side) in bright and dim bands, to make
# refraction visible. Fine texels (0.35 degrees, about half a pixel): Mitsuba filters its map
# bilinearly, mixtrace reads it piecewise constant (exactly what it samples), which on a coarse
# map would differ across every block edge.
W, H = 1024, 512
ys, xs = np.mgrid[0:H, 0:W]
palette = np.array([(1, .2, .1), (.1, 1, .2), (.2, .3, 1), (1, 1, .2)], np.float32)
env = palette[(xs // 64) % 4] * np.where((ys // 64) % 2 == 0, 2.0, 0.3)[:, :, None].astype(np.float32)
mi.Bitmap(env.astype(np.float32)).write('map.exr')


def icosphere(subdivisions):
    g = (1 + 5 ** 0.5) / 2
    v = [np.array(p, float) for a in (-1, 1) for b in (-g, g) for p in ((0, a, b), (a, b, 0), (b, 0, a))]
    faces = [(i, j, k) for i in range(12) for j in range(i + 1, 12) for k in range(j + 1, 12)
             if all(abs(np.linalg.norm(v[p] - v[q]) - 2) < 1e-9 for p, q in ((i, j), (j, k), (i, k)))]
    verts = [p / np.linalg.norm(p) for p in v]
    for _ in range(subdivisions):
        cache, finer = {}, []
        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = verts[a] + verts[b]
                verts.append(m / np.linalg.norm(m))
                cache[key] = len(verts) - 1
            return cache[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            finer += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        faces = finer
    out = []
    for a, b, c in faces:   # counter-clockwise seen from outside
        if np.dot(np.cross(verts[b] - verts[a], verts[c] - verts[a]), verts[a] + verts[b] + verts[c]) < 0:
            b, c = c, b
        out.append((a, b, c))
    return np.array(verts, np.float32), np.array(out, np.uint32)


P, F = icosphere(4)
with open('sphere.obj', 'w') as f:
    for p in P: f.write('v %.9g %.9g %.9g\n' % tuple(p))
    for p in P: f.write('vn %.9g %.9g %.9g\n' % tuple(p))
    for a, b, c in F: f.write('f %d//%d %d//%d %d//%d\n' % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1))


def gltf(roughness, ior):
    pos, nrm, idx = P.tobytes(), P.tobytes(), F.tobytes()
    data = pos + nrm + idx
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"],
            "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
                                                    "roughnessFactor": roughness},
                           "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                          "KHR_materials_ior": {"ior": ior},
                                          "KHR_materials_volume": {"thicknessFactor": 1}}}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(P), "type": "VEC3",
                           "min": P.min(0).tolist(), "max": P.max(0).tolist()},
                          {"bufferView": 1, "componentType": 5126, "count": len(P), "type": "VEC3"},
                          {"bufferView": 2, "componentType": 5125, "count": F.size, "type": "SCALAR"}],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(nrm)},
                            {"buffer": 0, "byteOffset": len(pos) + len(nrm), "byteLength": len(idx)}],
            "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," +
                         base64.b64encode(data).decode()}]}


EYE, TARGET, FOV = (0.4, 0.8, 3.2), (0, 0, 0), 40
worst = 0.0
print('working folder', os.getcwd())
for roughness, ior in [(0.0, 1.5), (0.3, 1.5), (0.5, 1.33), (0.15, 2.0)][:int(os.environ.get('CASES', 4))]:
    bsdf = ({'type': 'dielectric', 'int_ior': ior, 'ext_ior': 1.0} if roughness == 0 else
            {'type': 'roughdielectric', 'distribution': 'ggx', 'alpha': roughness ** 2, 'int_ior': ior,
             'ext_ior': 1.0, 'sample_visible': True})
    scene = mi.load_dict({
        'type': 'scene', 'integrator': {'type': 'path', 'max_depth': DEPTH, 'rr_depth': 1000},
        'emitter': {'type': 'envmap', 'filename': 'map.exr'},
        'ball': {'type': 'obj', 'filename': 'sphere.obj', 'bsdf': bsdf, 'face_normals': False},
        'sensor': {'type': 'perspective', 'fov': FOV,
                   'to_world': mi.ScalarTransform4f().look_at(origin=list(EYE), target=list(TARGET), up=[0, 1, 0]),
                   'film': {'type': 'hdrfilm', 'width': SIZE, 'height': SIZE, 'rfilter': {'type': 'box'}},
                   'sampler': {'type': 'independent', 'sample_count': SPP}}})
    m = np.array(mi.render(scene), np.float64)[:, :, :3]
    json.dump(gltf(roughness, ior), open('glass.gltf', 'w'))
    subprocess.run([BINARY, 'render', 'glass.gltf', '--env', 'map.exr', '--look-from', '%g,%g,%g' % EYE,
                    '--look-at', '%g,%g,%g' % TARGET, '--fov', str(FOV), '--width', str(SIZE), '--height', str(SIZE),
                    '--spp', str(SPP), '--max-depth', str(DEPTH), '--backend', 'cpu', '--no-png', '-q', '--out', 'mx.exr'],
                   check=True, env=dict(os.environ, XDG_RUNTIME_DIR=os.environ.get('XDG_RUNTIME_DIR', '/tmp')))
    x = np.array(mi.Bitmap('mx.exr'), np.float64)[:, :, :3]
    for name, img in (('mitsuba', m), ('mixtrace', x)):   # to look at: PNGs in the working folder
        mi.Bitmap((img * 0.5).astype(np.float32)).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8, True).write(
            '%s-r%.2f-ior%.2f.png' % (name, roughness, ior))
    blocks = lambda a: a.reshape(SIZE // 8, 8, SIZE // 8, 8, 3).mean((1, 3))
    diff = np.abs(blocks(m) - blocks(x)).max() / m.mean()
    worst = max(worst, diff)
    print('roughness %.2f ior %.2f: mean mitsuba %s mixtrace %s; largest 8x8-block difference %.2f %% of the mean'
          % (roughness, ior, np.round(m.mean((0, 1)), 4), np.round(x.mean((0, 1)), 4), 100 * diff))
print('largest difference %.2f %%' % (100 * worst))
sys.exit(0 if worst < 0.05 else 1)
