"""Running the mixtrace binary: renders (returning their stats JSON) and relMSE comparisons."""
import hashlib
import json
import os
import shutil
import subprocess
import tempfile


class Mixtrace:
    def __init__(self, binary):
        if not os.path.exists(binary):
            raise SystemExit(f"benchmark: no mixtrace binary at {binary} (build first: bash scripts/setup.sh)")
        # A private copy: rebuilding the project while a long benchmark runs must not change (or
        # break) the binary under measurement.
        self._dir = tempfile.mkdtemp(prefix="mixtrace-bench-bin-")
        self.binary = os.path.join(self._dir, "mixtrace")
        shutil.copy2(binary, self.binary)

    def identity(self):
        """What the references depend on: the exact binary (any change to the renderer rebuilds it)."""
        h = hashlib.sha256()
        with open(self.binary, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                h.update(block)
        return h.hexdigest()

    def render(self, scene, out, method, cfg, spp=None, seconds=None, seed=1, backend="vulkan", extra=()):
        """Renders `scene` to `out` (EXR) and returns its stats JSON. cfg: width, height, max_depth."""
        cmd = [self.binary, "render", scene, "--backend", backend, "--method", method,
               "--width", str(cfg["width"]), "--height", str(cfg["height"]), "--max-depth", str(cfg["max_depth"]),
               "--seed", str(seed), "-q", "--out", out, "--stats", out + ".json"] + [str(e) for e in extra]
        if spp is not None:
            cmd += ["--spp", str(spp)]
        if seconds is not None:
            cmd += ["--time", f"{seconds:.4f}"]
        subprocess.run(cmd, check=True)
        with open(out + ".json") as f:
            return json.load(f)

    def rel_mse(self, image, reference, error_map=None):
        """relMSE (docs/estimator.md section 8) of `image` against `reference`; optionally writes the per-pixel
        terms as a PFM error map."""
        cmd = [self.binary, "compare", image, reference, "--error-only"]
        if error_map:
            cmd += ["--error-map", error_map]
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout.split()
        return float(out[1])
