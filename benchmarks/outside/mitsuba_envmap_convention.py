#!/usr/bin/env python3
"""Checks mixtrace's environment-map convention against Mitsuba 3's `envmap` (the convention
shaders/shared/environment.h claims): the same equirectangular map, seen directly through a
narrow camera in several directions, with and without a turn about +Y (--env-rotate against
Mitsuba's to_world rotation), must give the same colours in both renderers.

Needs Mitsuba 3 from the Python package registry (not a Debian package, so not part of the test
suite):  python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy
Run:     /tmp/mi/bin/python benchmarks/outside/mitsuba_envmap_convention.py build/mixtrace
Exits 1 when a direction differs. Last run: docs/conventions.md ("Environment light").
"""
import base64, json, os, subprocess, sys, tempfile
import numpy as np
import mitsuba as mi

BINARY = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'build/mixtrace')
os.chdir(tempfile.mkdtemp(prefix='mixtrace-envmap-'))
mi.set_variant('scalar_rgb')
W, H = 64, 32
cols = [(1,0,0),(0,1,0),(0,0,1),(1,1,0)]        # u quarters: [0,.25) red, green, blue, yellow
img = np.zeros((H, W, 3), np.float32)
for y in range(H):
    for x in range(W):
        c = np.array(cols[x * 4 // W], np.float32)
        img[y, x] = c * (1.0 if y < H // 2 else 0.25)   # upper half bright
mi.Bitmap(img).write('map.exr')
# a glTF with one tiny triangle far below (mixtrace needs geometry)
pos = np.array([[0,-1000,0],[0.001,-1000,0],[0,-1000,0.001]], np.float32).tobytes()
g = {"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
     "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
     "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,-1000,0],"max":[0.001,-1000,0.001]}],
     "bufferViews":[{"buffer":0,"byteLength":36}],
     "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,"+base64.b64encode(pos).decode()}]}
json.dump(g, open('empty.gltf','w'))
# The axes fall on the map's block edges (both renderers then blend two blocks), the diagonals
# inside blocks.
views = {'+X':(1,0.3,0), '+Z':(0,0.3,1), '-X':(-1,0.3,0), '-Z':(0,0.3,-1), '-X down':(-1,-0.3,0),
         '+X+Z':(1,0.3,1), '-X+Z':(-1,0.3,1), '-X-Z':(-1,0.3,-1), '+X-Z down':(1,-0.4,-1)}
worst = 0.0
for rot in [0, 90]:
  for name, d in views.items():
    scene = mi.load_dict({'type':'scene','integrator':{'type':'path','max_depth':2},
        'emitter':{'type':'envmap','filename':'map.exr','to_world': mi.ScalarTransform4f().rotate([0,1,0], rot)},
        'sensor':{'type':'perspective','fov':5,'to_world':mi.ScalarTransform4f().look_at(origin=[0,0,0],target=list(d),up=[0,1,0]),
                  'film':{'type':'hdrfilm','width':8,'height':8,'rfilter':{'type':'box'}},'sampler':{'type':'independent','sample_count':16}}})
    m = np.array(mi.render(scene)).reshape(-1,3).mean(0)
    subprocess.run([BINARY,'render','empty.gltf','--env','map.exr','--env-rotate',str(rot),'--look-from','0,0,0',
                    '--look-at','%g,%g,%g'%d,'--fov','5','--width','8','--height','8','--spp','16','--backend','cpu','--no-png','-q','--out','mx.exr'],check=True,
                   env=dict(os.environ, XDG_RUNTIME_DIR=os.environ.get('XDG_RUNTIME_DIR', '/tmp')))
    x = np.array(mi.Bitmap('mx.exr')).reshape(-1,3).mean(0)
    worst = max(worst, float(np.abs(m - x).max()))
    print('rotate %3d  %-8s mitsuba %s  mixtrace %s' % (rot, name, np.round(m,3), np.round(x,3)))
print('largest difference %.4f' % worst)
sys.exit(0 if worst < 0.02 else 1)
