"""Mitsuba 3 side of the speed benchmark (benchmarks/speed.py), run by the Python of the virtual
environment that holds Mitsuba (speed.py creates it). One process per measurement:

    speed_mitsuba.py render SCENE --width W --height H --max-depth D --spp N [--variant V] [--out X.exr]
    speed_mitsuba.py calibrate SCENE --width W --height H --max-depth D --seconds T [--variant V]
    speed_mitsuba.py probe [--variant V]          # can this variant render at all? (exit status)
    speed_mitsuba.py means A.exr B.exr ...        # mean RGB of each image (mixtrace's renders)

Each prints one JSON object on its last line of output.

The scene is built from the glTF (bench/speed_gltf.py): the same triangles (PLY files with the
file's normals and texture coordinates), every material as Mitsuba's `principled` (base colour,
metallic, roughness from the pbrMetallicRoughness factors, or from the textures where there are
some: base colour sRGB-decoded, roughness from G and metallic from B of the metallic-roughness
texture, each times its factor) wrapped in `twosided` (mixtrace's BSDF is two-sided), emissive
triangles as one-sided `area` emitters of radiance emissiveFactor x emissiveStrength (times the
sRGB-decoded emissive texture where there is one), KHR_lights_punctual lights as `point`, `spot`
(cutoff = outer cone, beam width = inner cone) and `directional` emitters, the glTF camera
(vertical yfov: fov_axis 'y', looking down the node's -Z), a box pixel filter, the `independent`
sampler and the `path` integrator with max_depth = mixtrace's --max-depth (both count path
segments: 1 = emitters seen directly) and rr_depth = 1000, so Russian roulette never starts
(mixtrace has none either: every path runs to the maximum depth or escapes).

Timing: the JIT is warmed up first by a 1-spp render of the same scene at the same size (which
compiles and caches the kernels; the sample count and seed are not baked into them), then
`mi.render` is timed up to the image's conversion to a numpy array (which forces the evaluation)
and `dr.sync_thread()`. Renders above 64 spp run as several passes of at most 64 spp (memory),
each timed likewise; samples/s = width x height x spp / the summed time.
"""
import json
import os
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from bench import speed_gltf  # noqa: E402

PASS_SPP = 64


def _args(argv):
    opts = {"variant": "llvm_ad_rgb", "width": 320, "height": 240, "max_depth": 5, "spp": 16, "seconds": 3.0,
            "out": None, "seed": 0}
    pos = []
    i = 0
    while i < len(argv):
        a = argv[i]
        if a.startswith("--"):
            key = a[2:].replace("-", "_")
            val = argv[i + 1]
            opts[key] = type(opts[key])(val) if opts.get(key) is not None else val
            i += 2
        else:
            pos.append(a)
            i += 1
    return pos, opts


def _srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def build(mi, path, opts, workdir):
    s = speed_gltf.load(path)
    images = {}

    def image(tex_index):
        """The texture's image as a float array in [0, 1], (H, W, C)."""
        img = s["textures"][tex_index]["image"]
        if img not in images:
            fn = os.path.join(workdir, f"image{img}{s['images'][img]['ext']}")
            with open(fn, "wb") as f:
                f.write(s["images"][img]["data"])
            bmp = mi.Bitmap(fn)
            arr = np.array(bmp, dtype=np.float32)
            if arr.ndim == 2:
                arr = arr[:, :, None]
            if np.array(bmp).dtype == np.uint8:
                arr = arr / 255.0
            images[img] = arr
        return images[img]

    def bitmap(arr, tex_index):
        d = {"type": "bitmap", "bitmap": mi.Bitmap(np.ascontiguousarray(arr.astype(np.float32))), "raw": True}
        if s["textures"][tex_index]["nearest"]:
            d["filter_type"] = "nearest"
        return d

    def rgb(v):
        return {"type": "rgb", "value": [float(x) for x in v]}

    scene = {"type": "scene"}
    for k, mesh in enumerate(s["meshes"]):
        fn = os.path.join(workdir, f"mesh{k}.ply")
        speed_gltf.write_ply(fn, mesh)
        m = s["materials"][mesh["material"]] if mesh["material"] is not None else {
            "base_color": [1, 1, 1], "base_color_texture": None, "metallic": 1.0, "roughness": 1.0,
            "metallic_roughness_texture": None, "emission": [0, 0, 0], "emissive_texture": None}
        has_uv = mesh["uvs"] is not None
        if m["base_color_texture"] is not None and has_uv:
            a = _srgb_to_linear(image(m["base_color_texture"])[:, :, :3]) * np.array(m["base_color"], np.float32)
            base = bitmap(a, m["base_color_texture"])
        else:
            base = rgb(m["base_color"])
        if m["metallic_roughness_texture"] is not None and has_uv:
            a = image(m["metallic_roughness_texture"])
            rough = bitmap(a[:, :, 1:2] * m["roughness"], m["metallic_roughness_texture"])
            metal = bitmap(a[:, :, 2:3] * m["metallic"], m["metallic_roughness_texture"])
        else:
            rough, metal = float(m["roughness"]), float(m["metallic"])
        shape = {"type": "ply", "filename": fn, "face_normals": False,
                 "bsdf": {"type": "twosided", "material": {"type": "principled", "base_color": base,
                                                           "metallic": metal, "roughness": rough}}}
        if m["emissive_texture"] is not None and has_uv:
            a = _srgb_to_linear(image(m["emissive_texture"])[:, :, :3]) * np.array(m["emission"], np.float32)
            shape["emitter"] = {"type": "area", "radiance": bitmap(a, m["emissive_texture"])}
        elif max(m["emission"]) > 0:
            shape["emitter"] = {"type": "area", "radiance": rgb(m["emission"])}
        scene[f"mesh{k}"] = shape

    T = mi.ScalarTransform4f
    for k, light in enumerate(s["lights"]):
        p = np.array(light["position"])
        d = np.array(light["direction"])
        if light["type"] == "point":
            scene[f"light{k}"] = {"type": "point", "position": p.tolist(), "intensity": rgb(light["intensity"])}
        elif light["type"] == "spot":
            scene[f"light{k}"] = {"type": "spot", "intensity": rgb(light["intensity"]),
                                  "cutoff_angle": float(np.degrees(light["outer"])),
                                  "beam_width": float(np.degrees(light["inner"])),
                                  "to_world": T().look_at(origin=p.tolist(), target=(p + d).tolist(), up=light["up"])}
        elif light["type"] == "directional":
            scene[f"light{k}"] = {"type": "directional", "direction": d.tolist(), "irradiance": rgb(light["intensity"])}

    cam = s["camera"]
    if cam is None:
        raise SystemExit(f"speed_mitsuba: {path} has no perspective camera")
    p, f = np.array(cam["position"]), np.array(cam["forward"])
    scene["sensor"] = {"type": "perspective", "fov_axis": "y", "fov": float(np.degrees(cam["yfov"])),
                       "near_clip": 0.01, "far_clip": 1000.0,
                       "to_world": T().look_at(origin=p.tolist(), target=(p + f).tolist(), up=cam["up"]),
                       "film": {"type": "hdrfilm", "width": opts["width"], "height": opts["height"],
                                "rfilter": {"type": "box"}, "pixel_format": "rgb"},
                       "sampler": {"type": "independent", "sample_count": 1}}
    scene["integrator"] = {"type": "path", "max_depth": opts["max_depth"], "rr_depth": 1000}
    return mi.load_dict(scene), len(s["meshes"]), sum(len(m["indices"]) for m in s["meshes"])


def timed_render(mi, dr, scene, spp, seed):
    """Renders spp samples per pixel in passes of at most PASS_SPP; returns (seconds, image)."""
    total, acc, done, k = 0.0, None, 0, 0
    while done < spp:
        n = min(PASS_SPP, spp - done)
        t0 = time.perf_counter()
        img = np.array(mi.render(scene, spp=n, seed=seed * 1000 + k))
        dr.sync_thread()
        total += time.perf_counter() - t0
        acc = img * n if acc is None else acc + img * n
        done += n
        k += 1
    return total, acc / spp


def main(argv):
    pos, opts = _args(argv)
    cmd = pos[0]
    import mitsuba as mi
    import drjit as dr
    if cmd == "means":
        mi.set_variant("scalar_rgb")
        out = {}
        for fn in pos[1:]:
            a = np.array(mi.Bitmap(fn), dtype=np.float64)
            out[fn] = [float(x) for x in a[:, :, :3].reshape(-1, 3).mean(axis=0)]
        print(json.dumps(out))
        return 0
    mi.set_variant(opts["variant"])
    info = {"variant": opts["variant"], "mitsuba": mi.__version__, "drjit": dr.__version__}
    if opts["variant"].startswith("llvm"):
        info["llvm"] = ".".join(str(v) for v in dr.detail.llvm_version())
    workdir = tempfile.mkdtemp(prefix="mixtrace-speed-mi-")
    if cmd == "probe":
        from bench import speed_gltf as _  # noqa: F401
        scene = mi.load_dict({"type": "scene", "integrator": {"type": "path", "max_depth": 5, "rr_depth": 1000},
                              "sphere": {"type": "sphere", "bsdf": {"type": "twosided", "material": {"type": "principled"}}},
                              "light": {"type": "point", "position": [0, 3, 3]},
                              "sensor": {"type": "perspective", "to_world": mi.ScalarTransform4f().look_at(
                                  origin=[0, 0, 5], target=[0, 0, 0], up=[0, 1, 0]),
                                  "film": {"type": "hdrfilm", "width": 8, "height": 8}}})
        img = np.array(mi.render(scene, spp=2))
        info["mean"] = float(img.mean())
        print(json.dumps(info))
        return 0
    scene, shapes, triangles = build(mi, pos[1], opts, workdir)
    info.update(shapes=shapes, triangles=triangles)
    w, h = opts["width"], opts["height"]
    t0 = time.perf_counter()
    np.array(mi.render(scene, spp=1, seed=12345))  # warm-up: compiles (or loads) the kernels
    dr.sync_thread()
    info["warmup_seconds"] = time.perf_counter() - t0
    if cmd == "calibrate":
        spp = 4
        seconds, _ = timed_render(mi, dr, scene, spp, 1)
        if seconds < opts["seconds"] / 4:  # too short to time reliably: once more, about half as long
            spp = max(spp + 1, int(spp * opts["seconds"] / 2 / max(seconds, 1e-3)))
            seconds, _ = timed_render(mi, dr, scene, spp, 2)
        rate = w * h * spp / seconds
        info.update(samples_per_second=rate, spp=max(1, int(round(opts["seconds"] * rate / (w * h)))))
    else:
        spp = int(opts["spp"])
        seconds, img = timed_render(mi, dr, scene, spp, int(opts["seed"]))
        info.update(spp=spp, render_seconds=seconds, samples_per_second=w * h * spp / seconds,
                    mean=[float(x) for x in img[:, :, :3].reshape(-1, 3).mean(axis=0)])
        if opts["out"]:
            mi.Bitmap(img[:, :, :3].astype(np.float32)).write(opts["out"])
    print(json.dumps(info))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
