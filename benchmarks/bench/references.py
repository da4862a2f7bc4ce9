"""High-spp references, rendered by the project itself (the CPU backend, pt-power, a seed no
benchmark render uses) and cached under benchmarks/cache/. The cache key covers the scene file's
contents, the render settings, the scene's own options (`extra`, e.g. an environment map, and the
contents of the files they name) and the renderer binary, so a reference is rendered again when
the scene or the renderer changes."""
import hashlib
import os
import sys

REFERENCE_SEED = 987654


def reference(mx, scene, cfg, spp, cache_dir, extra=()):
    with open(scene, "rb") as f:
        key = hashlib.sha256(f.read())
    key.update(f"{cfg['width']}x{cfg['height']} d{cfg['max_depth']} {spp} {mx.identity()}".encode())
    for arg in extra:
        key.update(b"\0" + str(arg).encode())
        if os.path.isfile(str(arg)):
            with open(str(arg), "rb") as f:
                key.update(hashlib.sha256(f.read()).digest())
    os.makedirs(cache_dir, exist_ok=True)
    stem = os.path.basename(scene).split(".")[0]
    path = os.path.join(cache_dir, f"{stem}-d{cfg['max_depth']}-{key.hexdigest()[:16]}.exr")
    if not os.path.exists(path):
        print(f"benchmark: rendering the reference of {stem} (depth {cfg['max_depth']}, {spp} spp, CPU backend)...",
              file=sys.stderr, flush=True)
        tmp = path[:-len(".exr")] + ".partial.exr"   # renamed once complete: no half-written cache entry
        mx.render(scene, tmp, "pt-power", cfg, spp=spp, seed=REFERENCE_SEED, backend="cpu", extra=list(extra))
        for suffix in (".exr.json", ".png", ".exr"):
            os.replace(tmp[:-len(".exr")] + suffix, path[:-len(".exr")] + suffix)
    return path
