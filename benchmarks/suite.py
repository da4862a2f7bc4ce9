#!/usr/bin/env python3
"""The benchmark suite: what each method's accuracy costs in time, on every benchmark scene.

    python3 benchmarks/suite.py [--quick] [--out DIR] [--binary build/mixtrace] [--scenes a.gltf,b.gltf]
    python3 benchmarks/suite.py --paper [--quick] [--scenes VeachMIS,RGBSofa]   # the paper's table


For each scene and each method (pt-uniform, pt-power, learned, cv, cms) it renders at equal
samples per pixel and at equal time (every method gets pt-uniform's render time) against a
high-spp reference (rendered by mixtrace's CPU backend, cached in benchmarks/cache/ and rendered
again when the scene or the binary changes), and reports relMSE (docs/estimator.md section 8), spp
reached, time per sample and the overhead per sample relative to pt-uniform, in the form of the
paper's table. Charts: relMSE against time (log-log, one line per method), GPU time per sample
by pass group (where the overhead goes), and a false-colour relative-error image per method at
equal time beside the reference. Then sweeps of the accuracy knobs (cells, clusters, training
length, relative weighting, float atomics, max depth), each with error and time.

Everything is written to DIR (default benchmarks/results): report.md (tables), results.json (all
numbers), *.png (charts). --quick runs a tiny version (2 scenes, 32x24, a few spp, one value
per knob) in seconds, for CI: it checks that every method runs and every output is produced,
not speed. Exit status 1 when a render or an output is missing.

--paper runs the paper's protocol on its own scenes (converted under scenes/paper/, see
bench/paper.py): every method, the learning ones with our training and with the paper's, at equal
samples and equal time, with the published numbers beside ours, into DIR (default
benchmarks/results/paper).
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench import paper, plots, report  # noqa: E402
from bench.mixtrace import Mixtrace  # noqa: E402
from bench.references import reference  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
METHODS = ["pt-uniform", "pt-power", "learned", "cv", "cms"]
# The light-transport situations where the methods differ (scenes/README.md describes each).
SCENES = {
    "veach_mis.gltf": "Veach MIS: glossy plates against lights of four sizes",
    "many_lights.gltf": "many lights (34) behind occluders",
    "indirect_rgb.gltf": "coloured lights reaching the scene indirectly",
    "cornell_box.gltf": "a single large light",
    "punctual.gltf": "punctual lights (point and spot)",
    "textured.glb": "textured materials, several lights",
}

CONFIGS = {
    "full": dict(width=160, height=120, max_depth=5, spp=64, ref_spp=4096, seeds=2, series=[4, 8, 16, 32, 64, 128],
                 scenes=list(SCENES), knob_scenes=["veach_mis.gltf", "many_lights.gltf"],
                 knobs={"cells": [4, 8, 16, 32, 64], "max-clusters": [4, 8, 16, 32], "train-spp": [3, 7, 15, 0],
                        "relative-weighting": ["on", "off"], "float-atomics": ["on", "off"],
                        "max-depth": [2, 3, 5, 8]}),
    "quick": dict(width=32, height=24, max_depth=3, spp=4, ref_spp=64, seeds=1, series=[2, 4],
                  scenes=["veach_mis.gltf", "cornell_box.gltf"], knob_scenes=["veach_mis.gltf"],
                  knobs={"cells": [8, 16], "max-clusters": [2, 16], "train-spp": [1, 0],
                         "relative-weighting": ["on", "off"], "float-atomics": ["on", "off"], "max-depth": [2, 3]}),
}

# The paper's protocol (docs/estimator.md section 8) at 320x240, so that it runs on lavapipe in
# reasonable time (--width 640 --height 480 where time allows: the paper's size).
PAPER_CONFIGS = {
    "full": dict(width=320, height=240, max_depth=5, spp=128, ref_spp=4096, seeds=1, backend="vulkan",
                 scenes=["VeachMIS", "RGBSofa", "Bathroom", "ModernHall", "DiningRoom2"]),
    # Enough samples that the paper's one solve (after 16) happens and serves.
    "quick": dict(width=32, height=24, max_depth=3, spp=24, ref_spp=64, seeds=1, backend="vulkan",
                  scenes=["VeachMIS"]),
}

KNOB_HELP = {
    "cells": "cells along the scene's longest axis",
    "max-clusters": "light clusters (techniques) per cell",
    "train-spp": "training length: the last solve at or before this spp (0 = the whole first half)",
    "relative-weighting": "statistics weighted by throughput relative to the pixel",
    "float-atomics": "float atomics (on) or compare-and-swap loops (off) for the statistics",
    "max-depth": "longest path; cms's gain over pt-uniform at each depth",
}


def pass_groups(stats):
    """GPU ms of one render by pass group (plots.GROUPS). The statistics' share is the extra time
    per sample of the sample passes that gathered them over those that did not, times their count."""
    ms = dict(stats.get("gpu_pass_ms", {}))
    spp = stats["spp"]
    gathering = stats.get("cms_gathering_spp", 0)
    groups = {"trace": ms.pop("intersect", 0.0), "solve": ms.pop("solve", 0.0) + ms.pop("pixel_estimate", 0.0)}
    statistics = 0.0
    for stage, into in (("shade", "shade"), ("shadow", "trace")):
        plain, gathered = ms.pop(stage, 0.0), ms.pop(stage + "+statistics", 0.0)
        if gathering and spp > gathering:
            extra = max(0.0, gathered - plain / (spp - gathering) * gathering)
            statistics += extra
            gathered -= extra
        groups[into] = groups.get(into, 0.0) + plain + gathered
    groups["statistics"] = statistics
    groups["other"] = sum(ms.values())
    return {g: v / spp for g, v in groups.items()}


class Suite:
    def __init__(self, args, cfg):
        self.args, self.cfg = args, cfg
        self.mx = Mixtrace(args.binary)
        self.tmp = tempfile.mkdtemp(prefix="mixtrace-bench-")
        self.failures = []
        self.results = {"config": {k: v for k, v in cfg.items()}, "scenes": {}, "knobs": {}}

    def scene_path(self, name):
        return os.path.join(ROOT, "scenes", name)

    def render(self, scene, method, tag, cfg=None, **kw):
        out = os.path.join(self.tmp, f"{os.path.basename(scene).split('.')[0]}-{method}-{tag}.exr")
        stats = self.mx.render(scene, out, method, cfg or self.cfg, **kw)
        return out, stats

    def ref(self, scene, cfg=None, extra=()):
        """The cached high-spp reference; `extra`: the scene's own options (an environment map)."""
        return reference(self.mx, scene, cfg or self.cfg, self.cfg["ref_spp"], self.args.cache, extra)

    def scene(self, name):
        cfg, scene = self.cfg, self.scene_path(name)
        stem = name.split(".")[0]
        ref = self.ref(scene)
        rows, breakdown, series = {}, {}, {}
        for m in METHODS:   # equal samples per pixel
            errs, ms, groups = [], [], []
            for seed in range(1, cfg["seeds"] + 1):
                out, s = self.render(scene, m, f"spp{seed}", spp=cfg["spp"], seed=seed)
                errs.append(self.mx.rel_mse(out, ref))
                ms.append(1000.0 * s["render_seconds"] / s["spp"])
                groups.append(pass_groups(s))
            rows[m] = {"relmse_spp": sum(errs) / len(errs), "ms_per_sample": sum(ms) / len(ms),
                       "seconds": sum(ms) / len(ms) * cfg["spp"] / 1000.0, "estimator": s.get("estimator", m)}
            breakdown[m] = {g: sum(x.get(g, 0.0) for x in groups) / len(groups) for g in plots.GROUPS}
        budget = rows["pt-uniform"]["seconds"]
        panels = []
        for m in METHODS:   # equal time
            errs, spp = [], []
            for seed in range(1, cfg["seeds"] + 1):
                out, s = self.render(scene, m, f"time{seed}", seconds=budget, seed=100 + seed)
                emap = os.path.join(self.tmp, f"{stem}-{m}-error.pfm") if seed == 1 else None
                errs.append(self.mx.rel_mse(out, ref, error_map=emap))
                spp.append(s["spp"])
                if emap:
                    panels.append((f"{m} ({s['spp']} spp)", emap))
            rows[m]["relmse_time"] = sum(errs) / len(errs)
            rows[m]["spp_time"] = sum(spp) / len(spp)
        for m in METHODS:   # convergence
            series[m] = []
            for n in cfg["series"]:
                out, s = self.render(scene, m, f"series{n}", spp=n, seed=7)
                series[m].append((s["render_seconds"], self.mx.rel_mse(out, ref)))
        title = f"{stem} ({cfg['width']}x{cfg['height']}, depth {cfg['max_depth']})"
        out = lambda suffix: os.path.join(self.args.out, f"{stem}-{suffix}.png")
        plots.convergence(f"{title}: relMSE against time", series, out("convergence"))
        plots.pass_breakdown(f"{stem}: GPU time per sample at {cfg['spp']} spp", breakdown, out("passes"))
        plots.error_images(f"{stem}: relative error at equal time ({budget:.2f} s)", ref.replace(".exr", ".png"),
                           panels, out("error"))
        self.results["scenes"][stem] = {"description": SCENES.get(name, ""), "rows": rows, "breakdown": breakdown,
                                        "series": series, "equal_time_seconds": budget}

    def knobs(self):
        cfg = self.cfg
        for knob, values in cfg["knobs"].items():
            for name in cfg["knob_scenes"]:
                if knob == "max-clusters" and name != "many_lights.gltf" and "many_lights.gltf" in cfg["knob_scenes"]:
                    continue   # only a scene with more lights than clusters says anything
                scene, stem = self.scene_path(name), name.split(".")[0]
                points = []
                for v in values:
                    kcfg, extra = dict(cfg), []
                    if knob == "max-depth":
                        kcfg["max_depth"] = v
                    else:
                        extra = [f"--{knob}", v]
                    ref = self.ref(scene, kcfg)
                    errs, ms, base = [], [], []
                    for seed in range(1, cfg["seeds"] + 1):
                        out, s = self.render(scene, "cms", f"{knob}{v}-{seed}", cfg=kcfg, spp=cfg["spp"], seed=seed,
                                             extra=extra)
                        errs.append(self.mx.rel_mse(out, ref))
                        ms.append(1000.0 * s["render_seconds"] / s["spp"])
                        if knob == "max-depth":
                            out, s = self.render(scene, "pt-uniform", f"depth{v}-{seed}", cfg=kcfg, spp=cfg["spp"],
                                                 seed=seed)
                            base.append(self.mx.rel_mse(out, ref))
                    p = {"value": "all" if (knob == "train-spp" and v == 0) else v, "relmse": sum(errs) / len(errs),
                         "ms_per_sample": sum(ms) / len(ms)}
                    if base:
                        p["gain_vs_pt_uniform"] = sum(base) / max(sum(errs), 1e-30)
                    points.append(p)
                key = f"{knob}-{stem}"
                self.results["knobs"][key] = {"flag": f"--{knob}", "scene": stem, "points": points,
                                              "help": KNOB_HELP[knob]}
                path = os.path.join(self.args.out, f"knob-{key}.png")
                plots.knob(f"cms on {stem}: --{knob}", [str(p["value"]) for p in points],
                           [p["relmse"] for p in points], [p["ms_per_sample"] for p in points], path)


def machine(mx):
    """Where the numbers were measured: CPU, Vulkan device and driver (from a tiny render), OS."""
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    with tempfile.TemporaryDirectory() as tmp:
        s = mx.render(os.path.join(ROOT, "scenes", "cornell_box.gltf"), os.path.join(tmp, "m.exr"), "pt-power",
                      dict(width=8, height=8, max_depth=1), spp=1)
    version = subprocess.run([mx.binary, "--version"], capture_output=True, text=True).stdout.strip()
    return {"cpu": cpu, "cores": os.cpu_count(), "device": s.get("device", "?"), "os": platform.platform(),
            "renderer": version}


def markdown(results):
    cfg, m = results["config"], results["machine"]
    lines = [f"Measured on {m['cpu']} ({m['cores']} cores), Vulkan device {m['device']}, {m['os']}; {m['renderer']}.",
             f"Command: `{results['command']}` ({results['minutes']:.0f} min). Images {cfg['width']}x{cfg['height']}, "
             f"max depth {cfg['max_depth']}, {cfg['spp']} spp at equal samples, averaged over {cfg['seeds']} seed(s); "
             f"equal time = pt-uniform's time for {cfg['spp']} spp; references: {cfg['ref_spp']} spp, CPU backend, "
             "pt-power. Gains are relMSE ratios (higher is better); time is wall time per sample of the render.",
             "", "### Summary", "", report.summary_table(results["scenes"], METHODS), ""]
    for stem, r in results["scenes"].items():
        lines += [f"### {stem}: {r['description']}", "", report.scene_table(r["rows"], METHODS), "",
                  "GPU ms per sample by pass group (Vulkan timestamps; statistics = the extra time of the samples "
                  "that gathered them):", "", report.breakdown_table(r["breakdown"], plots.GROUPS), "",
                  f"![convergence]({stem}-convergence.png) ![passes]({stem}-passes.png)", "",
                  f"![error at equal time]({stem}-error.png)", ""]
    if results["knobs"]:
        lines += ["### Knobs (method cms)", ""]
        for key, k in results["knobs"].items():
            lines += [f"#### `{k['flag']}` on {k['scene']}: {k['help']}", "", report.knob_table(k), "",
                      f"![{key}](knob-{key}.png)", ""]
    return "\n".join(lines)


def check_outputs(out, results):
    """Every method of every scene has its numbers, and every chart exists and is not empty."""
    missing = []
    for stem, r in results["scenes"].items():
        for m in METHODS:
            row = r["rows"].get(m, {})
            for key in ("relmse_spp", "relmse_time", "ms_per_sample"):
                if not (row.get(key, -1) >= 0):
                    missing.append(f"{stem}/{m}/{key}")
        for suffix in ("convergence", "passes", "error"):
            path = os.path.join(out, f"{stem}-{suffix}.png")
            if not (os.path.exists(path) and os.path.getsize(path) > 1000):
                missing.append(path)
    for key in results["knobs"]:
        path = os.path.join(out, f"knob-{key}.png")
        if not (os.path.exists(path) and os.path.getsize(path) > 1000):
            missing.append(path)
    for name in ("report.md", "results.json"):
        if not os.path.exists(os.path.join(out, name)):
            missing.append(name)
    return missing


def run_paper(args):
    cfg = dict(PAPER_CONFIGS["quick" if args.quick else "full"])
    if args.scenes:
        cfg["scenes"] = args.scenes.split(",")
    for key in ("width", "height", "spp", "ref_spp", "backend"):
        if getattr(args, key):
            cfg[key] = getattr(args, key)
    args.out = args.out or (tempfile.mkdtemp(prefix="mixtrace-paper-quick-") if args.quick
                            else os.path.join(ROOT, "benchmarks", "results", "paper"))
    os.makedirs(args.out, exist_ok=True)
    suite = Suite(args, cfg)
    start = time.time()
    scenes, notes = paper.run(suite, cfg, cfg["scenes"])
    results = {"config": cfg, "scenes": scenes, "notes": notes, "machine": machine(suite.mx),
               "command": " ".join(["python3", "benchmarks/suite.py"] + sys.argv[1:]),
               "minutes": (time.time() - start) / 60.0}
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(results, f, indent=1)
    m = results["machine"]
    with open(os.path.join(args.out, "report.md"), "w") as f:
        f.write(f"Measured on {m['cpu']} ({m['cores']} cores), Vulkan device {m['device']}, {m['os']}; "
                f"{m['renderer']}. Command: `{results['command']}` ({results['minutes']:.0f} min).\n\n")
        f.write(paper.markdown(results, cfg) + "\n")
    for note in notes:
        print(f"benchmark: {note}", file=sys.stderr)
    print(f"benchmark: wrote {args.out}/report.md ({results['minutes']:.1f} min)", file=sys.stderr)
    return 0 if scenes else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="tiny and fast: checks that everything runs (CI)")
    ap.add_argument("--out", help="output folder (default: benchmarks/results, or a temporary one with --quick)")
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "mixtrace"))
    ap.add_argument("--cache", default=os.path.join(ROOT, "benchmarks", "cache"), help="reference cache folder")
    ap.add_argument("--scenes", help="comma-separated scene files under scenes/ (default: the suite's)")
    ap.add_argument("--no-knobs", action="store_true", help="skip the knob sweeps")
    ap.add_argument("--paper", action="store_true", help="the paper's table on its converted scenes (bench/paper.py)")
    ap.add_argument("--width", type=int, help="--paper: image width (default 320)")
    ap.add_argument("--height", type=int, help="--paper: image height (default 240)")
    ap.add_argument("--spp", type=int, help="--paper: samples per pixel at equal spp (default 128, the paper's)")
    ap.add_argument("--ref-spp", type=int, help="--paper: samples per pixel of the references (default 4096)")
    ap.add_argument("--backend", choices=["vulkan", "cpu"],
                    help="--paper: the backend of the method renders (default vulkan; the CPU backend renders the "
                         "same estimators, faster where Vulkan runs on lavapipe)")
    ap.add_argument("--report-only", action="store_true",
                    help="rewrite OUT/report.md from OUT/results.json without rendering (after a change of format)")
    args = ap.parse_args()
    if args.report_only:
        out = args.out or os.path.join(ROOT, "benchmarks", "results")
        with open(os.path.join(out, "results.json")) as f:
            results = json.load(f)
        with open(os.path.join(out, "report.md"), "w") as f:
            f.write(markdown(results))
        return 0
    paper_only = [f"--{k.replace('_', '-')}" for k in ("width", "height", "spp", "ref_spp", "backend")
                  if getattr(args, k)]
    if paper_only and not args.paper:
        ap.error(f"{', '.join(paper_only)}: only with --paper")
    if args.paper:
        return run_paper(args)
    cfg = dict(CONFIGS["quick" if args.quick else "full"])
    if args.scenes:
        cfg["scenes"] = args.scenes.split(",")
    args.out = args.out or (tempfile.mkdtemp(prefix="mixtrace-bench-quick-") if args.quick
                            else os.path.join(ROOT, "benchmarks", "results"))
    os.makedirs(args.out, exist_ok=True)
    suite = Suite(args, cfg)
    start = time.time()
    for name in cfg["scenes"]:
        print(f"benchmark: {name}", file=sys.stderr, flush=True)
        suite.scene(name)
    if not args.no_knobs:
        print("benchmark: knob sweeps", file=sys.stderr, flush=True)
        suite.knobs()
    suite.results["machine"] = machine(suite.mx)
    suite.results["command"] = " ".join(["python3", "benchmarks/suite.py"] + sys.argv[1:])
    suite.results["minutes"] = (time.time() - start) / 60.0
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(suite.results, f, indent=1)
    with open(os.path.join(args.out, "report.md"), "w") as f:
        f.write(markdown(suite.results))
    missing = check_outputs(args.out, suite.results)
    for m in missing:
        print(f"benchmark: missing output {m}", file=sys.stderr)
    print(f"benchmark: wrote {args.out}/report.md ({suite.results['minutes']:.1f} min)", file=sys.stderr)
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
