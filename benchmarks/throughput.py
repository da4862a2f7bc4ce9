#!/usr/bin/env python3
"""Throughput of the Vulkan backend on every shipped scene: samples and rays per second and GPU
time per pass (Vulkan timestamp queries), at 320x240, max depth 5 by default. Ratios between
scenes and passes are comparable within one run; absolute numbers depend on the machine's load.

    python3 benchmarks/throughput.py [--spp 64] [--repeat 3] [--binary build/mixtrace] [--markdown]
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def render(binary, scene, args, stats_path, backend="vulkan"):
    cmd = [binary, "render", scene, "--backend", backend, "--width", str(args.width), "--height", str(args.height),
           "--max-depth", str(args.max_depth), "--spp", str(args.spp), "--method", args.method,
           "-q", "--no-png", "--out", os.path.join(os.path.dirname(stats_path), "out.exr"), "--stats", stats_path]
    subprocess.run(cmd, check=True)
    with open(stats_path) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "mixtrace"))
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=240)
    ap.add_argument("--max-depth", type=int, default=5)
    ap.add_argument("--method", default="pt-power")
    ap.add_argument("--repeat", type=int, default=3, help="runs per scene; the fastest is reported")
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--compare-cpu", action="store_true",
                    help="also render each scene with --backend cpu and report both backends' samples/s")
    ap.add_argument("scenes", nargs="*")
    args = ap.parse_args()
    scenes = args.scenes or sorted(glob.glob(os.path.join(ROOT, "scenes", "*.gltf")) + glob.glob(os.path.join(ROOT, "scenes", "*.glb")))
    passes = ["generate", "prepare", "intersect", "shade", "shadow", "accumulate"]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in scenes:
            best = None
            for _ in range(args.repeat):
                s = render(args.binary, scene, args, os.path.join(tmp, "stats.json"))
                if best is None or s["samples_per_second"] > best["samples_per_second"]:
                    best = s
            if args.compare_cpu:
                cpu = None
                for _ in range(args.repeat):
                    c = render(args.binary, scene, args, os.path.join(tmp, "stats.json"), "cpu")
                    if cpu is None or c["samples_per_second"] > cpu["samples_per_second"]:
                        cpu = c
                best["cpu"] = cpu
            rows.append(best)
    device = rows[0]["device"] if rows else "?"
    print(f"# {device}, {args.width}x{args.height}, max depth {args.max_depth}, {args.spp} spp, method {args.method}, best of {args.repeat}")
    head = ["scene", "tris", "Msamples/s", "Mrays/s"] + [p + " %" for p in passes]
    if args.compare_cpu:
        head += ["CPU Msamples/s", "Vulkan/CPU"]
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
    else:
        print("  ".join(f"{h:>12}" for h in head))
    for s in rows:
        total = sum(s["gpu_pass_ms"].values()) or 1.0
        cells = [s["scene"], str(s["triangles"]), f"{s['samples_per_second'] / 1e6:.2f}", f"{s['rays_per_second'] / 1e6:.2f}"]
        cells += [f"{100 * s['gpu_pass_ms'].get(p, 0.0) / total:.0f}" for p in passes]
        if args.compare_cpu:
            cpu_rate = s["cpu"]["samples_per_second"]
            cells += [f"{cpu_rate / 1e6:.2f}", f"{s['samples_per_second'] / cpu_rate:.2f}x"]
        print(("| " + " | ".join(cells) + " |") if args.markdown else "  ".join(f"{c:>12}" for c in cells))


if __name__ == "__main__":
    sys.exit(main())
