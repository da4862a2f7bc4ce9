#!/usr/bin/env python3
"""A/B: two or more mixtrace binaries (or option sets) on one scene, run in alternation, so that
every variant sees the same background load. The per-change figures of benchmarks/README.md
("BVH layout", "What a pass costs on lavapipe") are measured this way.

    python3 benchmarks/ab.py SCENE --variant LABEL:BINARY[:ARGS] --variant ... 
                             [--spp 16] [--reps 7] [--method pt-power] [--json OUT.json]

    # e.g. the committed binary against a working copy, and the CPU backend beside them:
    cp build/mixtrace /tmp/before    # (then change, rebuild)
    python3 benchmarks/ab.py textured.glb --variant "before:/tmp/before:--schedule wavefront" \\
        --variant "after:build/mixtrace:--schedule wavefront" --variant "cpu:build/mixtrace:--backend cpu"

Each repeat renders every variant once (pt-power, 320x240, max depth 5 unless told otherwise), in
an order that rotates from repeat to repeat. Reported per variant: the median of the stats JSON's
samples_per_second (render time only), its range, the median of the per-repeat ratios to the first
variant (neighbouring runs share the machine's state, so their ratio is steadier than either rate
on a shared machine) and the median GPU time of each pass (Vulkan timestamps). SCENE is a file
under scenes/ or a path.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

from bench.mixtrace import Mixtrace

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def scene_path(scene):
    if os.path.exists(scene):
        return scene
    shipped = os.path.join(ROOT, "scenes", scene)
    if os.path.exists(shipped):
        return shipped
    raise SystemExit(f"ab: no scene {scene} (neither a path nor a file under scenes/)")


def run(args):
    cfg = {"width": args.width, "height": args.height, "max_depth": args.max_depth}
    variants = []
    for spec in args.variant:
        parts = spec.split(":", 2)
        label, binary, extra = parts + [""] * (3 - len(parts))
        if not label or not binary:
            raise SystemExit(f"ab: --variant {spec}: give LABEL:BINARY or LABEL:BINARY:ARGS")
        if any(label == v["label"] for v in variants):
            raise SystemExit(f"ab: two variants are labelled {label}")
        variants.append({"label": label, "mixtrace": Mixtrace(binary), "binary": binary,
                         "args": extra.split(), "rates": [], "pass_ms": {}})
    scene = scene_path(args.scene)
    out_dir = tempfile.mkdtemp(prefix="mixtrace-ab-")
    for rep in range(args.reps):
        for k in range(len(variants)):
            v = variants[(rep + k) % len(variants)]
            out = os.path.join(out_dir, v["label"] + ".exr")
            try:
                stats = v["mixtrace"].render(scene, out, args.method, cfg, spp=args.spp, seed=args.seed,
                                             extra=["--no-png"] + v["args"])
            except subprocess.CalledProcessError as e:
                raise SystemExit(f"ab: variant {v['label']}: mixtrace render failed (exit {e.returncode})")
            v["rates"].append(stats["samples_per_second"] / 1e6)
            for name, ms in (stats.get("gpu_pass_ms") or {}).items():
                v["pass_ms"].setdefault(name, []).append(ms)
    base = variants[0]["rates"]
    for v in variants:
        v["ratios"] = sorted(a / b for a, b in zip(v["rates"], base))
    return variants


def report(args, variants):
    base = variants[0]["label"]
    print(f"ab: {args.scene}, --method {args.method}, {args.width}x{args.height}, max depth {args.max_depth}, "
          f"{args.spp} spp, {args.reps} alternated repeats; M samples/s")
    for v in variants:
        r = v["rates"]
        print(f"  {v['label']:>12}: median {statistics.median(r):.3f} ({min(r):.3f}-{max(r):.3f}); "
              f"/ {base}: median {statistics.median(v['ratios']):.3f} "
              f"({' '.join(f'{x:.2f}' for x in v['ratios'])})")
        if v["pass_ms"]:
            print("  " + " " * 14 + "GPU ms per pass (medians): " +
                  " ".join(f"{name} {statistics.median(ms):.1f}" for name, ms in sorted(v["pass_ms"].items())))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", help="a file under scenes/ (e.g. veach_mis.gltf) or a path")
    ap.add_argument("--variant", action="append", required=True, metavar="LABEL:BINARY[:ARGS]",
                    help="a label, a mixtrace binary and its extra render options (split at spaces); "
                         "the first variant is the one the ratios divide by")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--reps", type=int, default=7, help="alternated repeats (default 7)")
    ap.add_argument("--method", default="pt-power")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--max-depth", type=int, default=5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--json", help="also write every run's figures here")
    args = ap.parse_args()
    if args.reps < 1 or args.spp < 1:
        raise SystemExit("ab: --reps and --spp must be at least 1")
    if len(args.variant) < 2:
        raise SystemExit("ab: give at least two --variant")
    variants = run(args)
    report(args, variants)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"scene": args.scene, "method": args.method, "spp": args.spp, "reps": args.reps,
                       "width": args.width, "height": args.height, "max_depth": args.max_depth,
                       "variants": [{k: v[k] for k in ("label", "binary", "args", "rates", "ratios", "pass_ms")}
                                    for v in variants]}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
