#!/usr/bin/env python3
"""Why cv/cms miss the paper's gains on Veach MIS (issue 13): per-depth relMSE, reference noise,
per-cell sample counts and cv's grid resolution, at 320x240 on the CPU backend.

Usage: python3 veachmis_why.py [--bin build/mixtrace] [--work /tmp/veachmis-why] [--no-validate]
Renders (one at a time) what is missing in --work, then prints markdown tables. relMSE is the
benchmark's own (benchmarks/bench/mixtrace.py: `mixtrace compare --error-only`, the paper's metric
of docs/estimator.md section 8: channel-mean (img-ref)^2/(ref^2+1e-4), 0.1% largest pixels dropped).
"""
import argparse
import json
import os
import subprocess
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
from bench.mixtrace import Mixtrace  # noqa: E402  (only numpy-free module needed)

SCENE = os.path.join(ROOT, "scenes/paper/VeachMIS/VeachMIS.gltf")
W, H, SPP, REF_SPP = 320, 240, 64, 1024
METHODS = ["pt-uniform", "cv", "cms", "pt-bvh"]
SEEDS = [1, 2]
DEPTHS = [2, 3, 5]
REF_SEED_A, REF_SEED_B, REF_SEED_C = 987654, 987655, 987656   # A = the benchmark's reference seed
CELLS = ["8", "16", "auto"]


def render(args, name, method, depth, spp, seed, extra=()):
    out = os.path.join(args.work, name + ".exr")
    if not os.path.exists(out):
        cmd = [args.bin, "render", SCENE, "--backend", "cpu", "--method", method, "--width", str(W),
               "--height", str(H), "--max-depth", str(depth), "--spp", str(spp), "--seed", str(seed),
               "-q", "--no-png", "--out", out, "--stats", out + ".json"] + list(extra)
        t = time.time()
        subprocess.run(cmd, check=True)
        print(f"  {time.time() - t:6.1f} s  {' '.join(cmd[2:])}", file=sys.stderr, flush=True)
    with open(out + ".json") as f:
        return out, json.load(f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "mixtrace"))
    ap.add_argument("--work", default="/tmp/veachmis-why")
    ap.add_argument("--no-validate", action="store_true", help="skip the 4096-spp validation references")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    mx = Mixtrace(args.bin)
    res = {"refs": {}, "rel": {}, "stats": {}}

    # References: A (the benchmark's seed) and an independent B per depth; C at 4096 spp checks the correction.
    refs = {}
    for d in DEPTHS:
        refs[(d, "A")] = render(args, f"ref-d{d}-A", "pt-power", d, REF_SPP, REF_SEED_A)[0]
        refs[(d, "B")] = render(args, f"ref-d{d}-B", "pt-power", d, REF_SPP, REF_SEED_B)[0]
        if not args.no_validate and d in (2, 5):
            refs[(d, "C")] = render(args, f"ref-d{d}-C4096", "pt-power", d, 4 * REF_SPP, REF_SEED_C)[0]

    # Method renders: 64 spp, seeds 1, 2, default settings (our training, auto cells).
    for d in DEPTHS:
        for m in METHODS:
            for s in SEEDS:
                out, st = render(args, f"{m}-d{d}-s{s}", m, d, SPP, s)
                res["stats"][f"{m}-d{d}-s{s}"] = st
                for r in ("A", "B", "C"):
                    if (d, r) in refs:
                        res["rel"][f"{m}-d{d}-s{s}-{r}"] = mx.rel_mse(out, refs[(d, r)])
    # cv's grid resolution at depth 5.
    for c in CELLS[:-1]:
        for s in SEEDS:
            out, st = render(args, f"cv-c{c}-d5-s{s}", "cv", 5, SPP, s, ["--cells", c])
            res["stats"][f"cv-c{c}-d5-s{s}"] = st
            for r in ("A", "B", "C"):
                if (5, r) in refs:
                    res["rel"][f"cv-c{c}-d5-s{s}-{r}"] = mx.rel_mse(out, refs[(5, r)])
    # Reference against reference.
    for d in DEPTHS:
        res["refs"][f"d{d}-A-vs-B"] = mx.rel_mse(refs[(d, "A")], refs[(d, "B")])
        res["refs"][f"d{d}-B-vs-A"] = mx.rel_mse(refs[(d, "B")], refs[(d, "A")])
        if (d, "C") in refs:
            res["refs"][f"d{d}-A-vs-C"] = mx.rel_mse(refs[(d, "A")], refs[(d, "C")])
            res["refs"][f"d{d}-B-vs-C"] = mx.rel_mse(refs[(d, "B")], refs[(d, "C")])
    with open(os.path.join(args.work, "veachmis_why.json"), "w") as f:
        json.dump(res, f, indent=1)
    report(res)


def mean(v):
    return sum(v) / len(v)


def report(res):
    rel = res["rel"]

    def err(m, d, r="A", s=None):
        return rel[f"{m}-d{d}-s{s}-{r}"] if s else mean([rel[f"{m}-d{d}-s{k}-{r}"] for k in SEEDS])

    print("\n### 1. relMSE per max depth (64 spp, reference A: 1024-spp pt-power, seed 987654)\n")
    print("| max depth | " + " | ".join(f"{m} (s1 / s2)" for m in METHODS) + " | " +
          " | ".join(f"gain {m}" for m in METHODS[1:]) + " |")
    print("|---|" + "---|" * (2 * len(METHODS) - 1))
    for d in DEPTHS:
        u = err("pt-uniform", d)
        cells = [f"{err(m, d):.5f} ({err(m, d, s=1):.5f} / {err(m, d, s=2):.5f})" for m in METHODS]
        gains = [f"{u / err(m, d):.2f}x" for m in METHODS[1:]]
        print(f"| {d} | " + " | ".join(cells) + " | " + " | ".join(gains) + " |")

    print("\n### 2. Reference noise\n")
    print("| max depth | relMSE(A vs B) | relMSE(B vs A) | one reference's share | relMSE(A vs C4096) | relMSE(B vs C4096) |")
    print("|---|---|---|---|---|---|")
    share = {}
    for d in DEPTHS:
        ab, ba = res["refs"][f"d{d}-A-vs-B"], res["refs"][f"d{d}-B-vs-A"]
        share[d] = (ab + ba) / 4.0
        ac = res["refs"].get(f"d{d}-A-vs-C")
        bc = res["refs"].get(f"d{d}-B-vs-C")
        fmt = lambda v: f"{v:.5f}" if v is not None else "-"
        print(f"| {d} | {ab:.5f} | {ba:.5f} | {share[d]:.5f} | {fmt(ac)} | {fmt(bc)} |")
    print("\nGains: measured against A, against B, corrected (A, mean over seeds, minus one reference's share),"
          " and against the 4096-spp reference C where it exists\n")
    print("| max depth | method | vs A | vs B | corrected (A - share) | vs C (4096 spp) |")
    print("|---|---|---|---|---|---|")
    for d in DEPTHS:
        for m in METHODS[1:]:
            ga = err("pt-uniform", d, "A") / err(m, d, "A")
            gb = err("pt-uniform", d, "B") / err(m, d, "B")
            gc = (err("pt-uniform", d, "A") - share[d]) / (err(m, d, "A") - share[d])
            gv = f"{err('pt-uniform', d, 'C') / err(m, d, 'C'):.2f}x" if f"{m}-d{d}-s1-C" in rel else "-"
            print(f"| {d} | {m} | {ga:.2f}x | {gb:.2f}x | {gc:.2f}x | {gv} |")

    print("\n### 3. Cells and pairs at max depth 5 (seed 1; seed 2 in brackets)\n")
    keys = ["cms_grid_cells", "cms_cells_used", "cms_pairs_used", "cms_pair_samples", "cms_cv_techniques",
            "cms_techniques", "cms_gathering_spp", "cms_pair_refused_samples", "cms_pair_remainder_samples"]
    runs = [("cv", "cv-d5"), ("cms", "cms-d5")] + [(f"cv --cells {c}", f"cv-c{c}-d5") for c in CELLS[:-1]]
    print("| run | " + " | ".join(keys) + " | pair samples / pair | relMSE vs A | gain vs A | gain vs C |")
    print("|---|" + "---|" * (len(keys) + 4))
    u5 = {r: err("pt-uniform", 5, r) for r in ("A", "C") if "pt-uniform-d5-s1-" + r in rel}
    for label, key in runs:
        s1, s2 = res["stats"][f"{key}-s1"], res["stats"][f"{key}-s2"]
        vals = [f"{s1.get(k)} ({s2.get(k)})" if s1.get(k) != s2.get(k) else f"{s1.get(k)}" for k in keys]
        per = [s["cms_pair_samples"] / s["cms_pairs_used"] for s in (s1, s2)]
        e = {r: mean([rel[f"{key}-s{k}-{r}"] for k in SEEDS]) for r in u5}
        gc = f"{u5['C'] / e['C']:.2f}x" if "C" in e else "-"
        print(f"| {label} | " + " | ".join(vals) + f" | {per[0]:.1f} ({per[1]:.1f}) | {e['A']:.5f} | "
              f"{u5['A'] / e['A']:.2f}x | {gc} |")
    secs = {k: v["render_seconds"] for k, v in res["stats"].items()}
    print("\nRender seconds (64 spp): " + ", ".join(f"{k} {v:.1f}" for k, v in sorted(secs.items())))


if __name__ == "__main__":
    main()
