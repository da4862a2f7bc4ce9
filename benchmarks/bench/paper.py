"""The paper's table, side by side (issue 13 point 4; docs/estimator.md section 8).

The protocol of Hua, Grittmann and Slusallek 2023 on their own scenes (converted to glTF under
scenes/paper/): max depth 5, one light and one BSDF sample per vertex, equal samples per pixel
(128 in the paper) and equal time (every method gets pt-uniform's time), relMSE with the 0.1 %
largest per-pixel errors dropped, against a high-spp reference. Each learning method runs twice:
with our training (iterations of doubling length, re-solved) and with the paper's (`--training
paper`: 16 spp of statistics, one solve). The paper's published numbers stand beside ours; its
method is the control variate with uniform selection over emissive triangles, our `cv` with its
training, against `pt-uniform`. A scene that needs more than its glTF file (DiningRoom2's sky)
gets its options from SCENE_ARGS, in every render of it, the reference's included.
"""
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# The paper's table (slides in ../shared/seeds/; docs/estimator.md section 8): equal-spp gain,
# equal-time gain and time overhead of its method over a balance-heuristic path tracer with
# uniform light selection, at 640x480.
PUBLISHED = {
    "VeachMIS": {"equal_spp": 1.78, "equal_time": 1.60, "overhead_percent": 16.82},
    "RGBSofa": {"equal_spp": 2.17, "equal_time": 2.03, "overhead_percent": 11.72},
    "Bathroom": {"equal_spp": 1.03, "equal_time": 1.01, "overhead_percent": 13.65},
    "ModernHall": {"equal_spp": 3.52, "equal_time": 3.28, "overhead_percent": 15.27},
    "DiningRoom2": {"equal_spp": 2.20, "equal_time": 1.90, "overhead_percent": 15.46},
}

# Options a scene needs beyond its file, given to every render of it (the reference's too; the
# reference cache's key covers them and the files they name). Paths are relative to the repository.
SCENE_ARGS = {
    # Its sky, seen through the window: the source's Skydome.pfm in mixtrace's map convention,
    # radiance unscaled and unturned (scenes/paper/README.md); a glTF file cannot name it.
    "DiningRoom2": ["--env", "scenes/paper/DiningRoom2/Skydome.exr"],
}

PLAIN_METHODS = ["pt-uniform", "pt-power", "pt-bvh"]
LEARNING_METHODS = ["learned", "cv", "cms"]
TRAININGS = {"ours": [], "paper": ["--training", "paper"]}


def scene_file(name):
    """The converted scene, or None where it has not been converted (scenes/paper/<name>/)."""
    for ext in (".gltf", ".glb"):
        path = os.path.join(ROOT, "scenes", "paper", name, name + ext)
        if os.path.exists(path):
            return path
    return None


def scene_args(name):
    """SCENE_ARGS of a scene, its paths made absolute (so that any working directory serves)."""
    args = list(SCENE_ARGS.get(name, []))
    for i in range(1, len(args)):
        if args[i - 1] == "--env":
            args[i] = os.path.join(ROOT, *args[i].split("/"))
    return args


def available_methods(binary):
    """The methods this binary knows (pt-bvh arrives with the light BVH)."""
    text = subprocess.run([binary, "--help"], capture_output=True, text=True).stdout
    return [m for m in PLAIN_METHODS + LEARNING_METHODS if m in text]


def variants(methods):
    """(label, method, extra arguments): the plain methods once, the learning ones per training."""
    out = [(m, m, []) for m in methods if m in PLAIN_METHODS]
    for training, extra in TRAININGS.items():
        out += [(f"{m} ({training} training)", m, extra) for m in methods if m in LEARNING_METHODS]
    return out


def run(suite, cfg, scenes):
    """Renders every variant of every converted scene at equal spp and equal time; returns the
    results (and notes for the scenes left out)."""
    results, notes = {}, []
    methods = available_methods(suite.mx.binary)
    if "pt-bvh" not in methods:
        notes.append("pt-bvh: not in this binary yet (the light BVH of issue 13 point 2)")
    for name in scenes:
        path = scene_file(name)
        if path is None:
            notes.append(f"{name}: not converted yet (scenes/paper/convert_seesharp.py)")
            continue
        own = scene_args(name)
        ref = suite.ref(path, cfg, extra=own)
        rows = {}
        for label, method, extra in variants(methods):
            errs, ms = [], []
            for seed in range(1, cfg["seeds"] + 1):
                out, s = suite.render(path, method, f"paper-spp-{label}-{seed}", cfg=cfg, spp=cfg["spp"], seed=seed,
                                      backend=cfg.get("backend", "vulkan"), extra=extra + own)
                errs.append(suite.mx.rel_mse(out, ref))
                ms.append(1000.0 * s["render_seconds"] / s["spp"])
            rows[label] = {"method": method, "relmse_spp": sum(errs) / len(errs), "ms_per_sample": sum(ms) / len(ms),
                           "estimator": s.get("estimator", method)}
        budget = rows["pt-uniform"]["ms_per_sample"] * cfg["spp"] / 1000.0
        for label, method, extra in variants(methods):
            errs, spp = [], []
            for seed in range(1, cfg["seeds"] + 1):
                out, s = suite.render(path, method, f"paper-time-{label}-{seed}", cfg=cfg, seconds=budget,
                                      seed=100 + seed, backend=cfg.get("backend", "vulkan"), extra=extra + own)
                errs.append(suite.mx.rel_mse(out, ref))
                spp.append(s["spp"])
            rows[label]["relmse_time"] = sum(errs) / len(errs)
            rows[label]["spp_time"] = sum(spp) / len(spp)
        results[name] = {"scene": os.path.relpath(path, ROOT), "scene_args": SCENE_ARGS.get(name, []), "rows": rows,
                         "equal_time_seconds": budget, "published": PUBLISHED.get(name)}
    return results, notes


def _gain(base, value):
    return f"{base / value:.2f}x" if base and value and value > 0 else "-"


def markdown(paper, cfg):
    """The paper's table with ours beside it, then every variant's numbers per scene."""
    lines = [f"Images {cfg['width']}x{cfg['height']}, max depth {cfg['max_depth']}, {cfg['spp']} spp at equal "
             f"samples, equal time = pt-uniform's time for {cfg['spp']} spp, {cfg['seeds']} seed(s); references "
             f"{cfg['ref_spp']} spp (CPU backend, pt-power); method renders on the "
             f"{cfg.get('backend', 'vulkan')} backend. Gains are relMSE ratios against pt-uniform (higher is "
             "better). The published numbers are the paper's, at 640x480 with its own renderer.", "",
             "| scene | published: equal spp / equal time / overhead | cv, paper training | cv, ours | "
             "cms, ours | pt-bvh | overhead of cms (ours) |", "|---|---|---|---|---|---|---|"]
    for name, r in paper["scenes"].items():
        rows, pub = r["rows"], r["published"] or {}
        u = rows["pt-uniform"]

        def both(label):
            row = rows.get(label)
            if not row:
                return "-"
            return f"{_gain(u['relmse_spp'], row['relmse_spp'])} / {_gain(u['relmse_time'], row['relmse_time'])}"

        cms = rows.get("cms (ours training)")
        overhead = f"{(cms['ms_per_sample'] / u['ms_per_sample'] - 1.0) * 100.0:+.1f} %" if cms else "-"
        published = (f"{pub['equal_spp']:.2f}x / {pub['equal_time']:.2f}x / {pub['overhead_percent']:.1f} %"
                     if pub else "-")
        lines.append(f"| {name} | {published} | {both('cv (paper training)')} | {both('cv (ours training)')} | "
                     f"{both('cms (ours training)')} | {both('pt-bvh')} | {overhead} |")
    lines += ["", "Each cell of ours: gain at equal spp / gain at equal time.", ""]
    for note in paper["notes"]:
        lines.append(f"- {note}")
    for name, r in paper["scenes"].items():
        u = r["rows"]["pt-uniform"]
        args = "".join(f" {a}" for a in r.get("scene_args", []))
        lines += ["", f"#### {name} (`{r['scene']}{args}`; equal time {r['equal_time_seconds']:.2f} s)", "",
                  "| variant | estimator | relMSE, equal spp | gain | relMSE, equal time | spp reached | gain | "
                  "ms per sample | overhead |", "|---|---|---|---|---|---|---|---|---|"]
        for label, row in r["rows"].items():
            overhead = (row["ms_per_sample"] / u["ms_per_sample"] - 1.0) * 100.0
            lines.append(f"| {label} | {row['estimator']} | {row['relmse_spp']:.4g} | "
                         f"{_gain(u['relmse_spp'], row['relmse_spp'])} | {row['relmse_time']:.4g} | "
                         f"{row['spp_time']:.0f} | {_gain(u['relmse_time'], row['relmse_time'])} | "
                         f"{row['ms_per_sample']:.1f} | {overhead:+.1f} % |")
    return "\n".join(lines)
