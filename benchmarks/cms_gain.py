#!/usr/bin/env python3
"""What controlled mixture sampling buys, per scene, in the form of the paper's table: relMSE
(cms.md section 8) of every method against a high-spp reference at equal samples per pixel and at
equal time, the gain of each method over a baseline, and its time per sample relative to
pt-uniform, with the GPU time per pass (Vulkan timestamp queries) that shows where the overhead
goes. All methods of one scene run back to back, so their ratios are comparable; the absolute
times depend on the machine's load.

    python3 benchmarks/cms_gain.py [--spp 64] [--width 160 --height 120] [--seeds 2] [scenes...]

References are rendered once by the CPU backend (pt-power, --ref-spp, another seed) and cached
under benchmarks/cache/, keyed by scene file contents, size, depth, spp and the binary's version.
"""
import argparse
import glob
import hashlib
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
METHODS = ["pt-uniform", "pt-power", "learned", "cv", "cms"]


def run(binary, scene, args, method, out, spp=None, seconds=None, seed=1, backend="vulkan", extra=()):
    cmd = [binary, "render", scene, "--backend", backend, "--method", method, "--width", str(args.width),
           "--height", str(args.height), "--max-depth", str(args.max_depth), "--seed", str(seed),
           "-q", "--no-png", "--out", out, "--stats", out + ".json"] + list(extra)
    if spp is not None:
        cmd += ["--spp", str(spp)]
    if seconds is not None:
        cmd += ["--time", str(seconds), "--spp", "1000000"]
    subprocess.run(cmd, check=True)
    with open(out + ".json") as f:
        return json.load(f)


def rel_mse(binary, image, reference):
    out = subprocess.run([binary, "compare", image, reference, "--error-only"], check=True, capture_output=True,
                         text=True).stdout.split()
    return float(out[1])


def reference(binary, scene, args):
    version = subprocess.run([binary, "--version"], check=True, capture_output=True, text=True).stdout.strip()
    with open(scene, "rb") as f:
        key = hashlib.sha256(f.read() + f"{args.width}x{args.height} d{args.max_depth} {args.ref_spp} {version}".encode())
    cache = os.path.join(ROOT, "benchmarks", "cache")
    os.makedirs(cache, exist_ok=True)
    path = os.path.join(cache, os.path.basename(scene).split(".")[0] + "-" + key.hexdigest()[:12] + ".exr")
    if not os.path.exists(path):
        print(f"rendering the reference of {os.path.basename(scene)} ({args.ref_spp} spp, CPU)...", file=sys.stderr)
        run(binary, scene, args, "pt-power", path, spp=args.ref_spp, seed=987654, backend="cpu")
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "mixtrace"))
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--max-depth", type=int, default=5)
    ap.add_argument("--seeds", type=int, default=2, help="independent renders per method; relMSE is averaged")
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("scenes", nargs="*")
    args = ap.parse_args()
    methods = args.methods.split(",")
    scenes = args.scenes or sorted(glob.glob(os.path.join(ROOT, "scenes", "*.gltf")) +
                                   glob.glob(os.path.join(ROOT, "scenes", "*.glb")))
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            ref = reference(args.binary, scene, args)
            rows = {}
            for m in methods:   # equal samples per pixel
                errs, secs, passes = [], [], {}
                for seed in range(1, args.seeds + 1):
                    out = os.path.join(tmp, f"{m}-{seed}.exr")
                    s = run(args.binary, scene, args, m, out, spp=args.spp, seed=seed)
                    errs.append(rel_mse(args.binary, out, ref))
                    secs.append(s["render_seconds"])
                    for k, v in s.get("gpu_pass_ms", {}).items():
                        passes[k] = passes.get(k, 0.0) + v / args.seeds
                rows[m] = {"rel_mse": sum(errs) / len(errs), "seconds": sum(secs) / len(secs), "passes": passes}
            budget = rows["pt-uniform"]["seconds"] if "pt-uniform" in rows else None
            for m in methods:   # equal time: each method gets pt-uniform's time for args.spp
                if budget is None:
                    break
                errs, spp = [], []
                for seed in range(1, args.seeds + 1):
                    out = os.path.join(tmp, f"{m}-t{seed}.exr")
                    s = run(args.binary, scene, args, m, out, seconds=budget, seed=100 + seed)
                    errs.append(rel_mse(args.binary, out, ref))
                    spp.append(s["spp"])
                rows[m]["rel_mse_equal_time"] = sum(errs) / len(errs)
                rows[m]["spp_equal_time"] = sum(spp) / len(spp)
            name = os.path.basename(scene)
            print(f"\n### {name} ({args.width}x{args.height}, depth {args.max_depth}, {args.spp} spp, "
                  f"{args.seeds} seeds; equal time = pt-uniform's {budget:.2f} s)\n")
            print("| method | relMSE (equal spp) | gain vs pt-uniform | gain vs pt-power | relMSE (equal time) | spp reached "
                  "| equal-time gain vs pt-uniform | equal-time gain vs pt-power | time/sample vs pt-uniform |")
            print("|---|---|---|---|---|---|---|---|---|")
            base, power = rows.get("pt-uniform"), rows.get("pt-power")
            for m in methods:
                r = rows[m]
                g = lambda b, key: f"{b[key] / r[key]:.2f}x" if b and key in r and r[key] > 0 else "-"
                print(f"| {m} | {r['rel_mse']:.4g} | {g(base, 'rel_mse')} | {g(power, 'rel_mse')} | "
                      f"{r.get('rel_mse_equal_time', float('nan')):.4g} | {r.get('spp_equal_time', 0):.0f} | "
                      f"{g(base, 'rel_mse_equal_time')} | {g(power, 'rel_mse_equal_time')} | "
                      f"{r['seconds'] / base['seconds']:.2f} |" if base else "")
            names = sorted({k for r in rows.values() for k in r["passes"]})
            print("\nGPU ms per pass at equal spp (sum over the render):\n")
            print("| method | " + " | ".join(names) + " | total |")
            print("|---|" + "---|" * (len(names) + 1))
            for m in methods:
                p = rows[m]["passes"]
                print(f"| {m} | " + " | ".join(f"{p.get(k, 0):.0f}" for k in names) + f" | {sum(p.values()):.0f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
