#!/usr/bin/env python3
"""Speed: mixtrace's Vulkan renderer (each schedule), its CPU backend and Mitsuba 3, in one run on one
machine, on the shipped scenes at 320x240, max depth 5: samples per second and their ratios, on an
idle machine and with a competing CPU-bound process on every core (how throughput holds under load).

    python3 benchmarks/speed.py [--quick] [--binary build/mixtrace] [--out DIR] [--venv /tmp/mi]
                                [--scenes a.gltf,b.glb] [--seconds 3] [--repeat 3] [--no-load]

- mixtrace: `mixtrace render SCENE --method pt-power --width 320 --height 240 --max-depth 5 --spp N`
  with `--backend vulkan --schedule auto` (the default: on a CPU device the wavefront for the first
  submission, then the schedule its ray count picks), `--schedule wavefront`, `--schedule fused` and
  `--backend cpu`; samples/s is the stats JSON's `samples_per_second` (render time, set-up excluded).
- Mitsuba 3 (llvm_ad_rgb; scalar_rgb if that cannot run here, which the report then says): the same
  scene built from the glTF by bench/speed_mitsuba.py (same triangles, `principled` materials from
  the glTF factors and textures as the speed stand-in for the glTF BRDF, area/point/spot/directional
  emitters, the glTF camera, box filter), `path` integrator, max_depth 5, Russian roulette off
  (rr_depth 1000; mixtrace has none). JIT warmed up by a 1-spp render, then `mi.render` timed.
  Set-up: a virtual environment (default /tmp/mi, as benchmarks/outside/ uses) with `mitsuba` and
  `numpy` from the Python package registry, created when missing. Dr.Jit's LLVM backend needs
  LLVM >= 16 here (LLVM 15, which Debian 12's Mesa uses, aborts on an `fminimum` it cannot select
  in the path integrator); when the probe render fails and apt-get is available to root, the set-up
  installs Debian's libllvm19 (beside LLVM 15: Mesa keeps its own) and tries again.
- Each renderer's sample count is calibrated once per scene (a short render) to take about
  --seconds on the idle machine; the loaded condition renders the same counts. Every measurement
  is repeated --repeat times, interleaved (scene by scene, renderers in a rotating order) so that
  all renderers see the same background load; the best run is reported, all are in results.json.
- Under load: one `while True: pass` Python process per core (os.cpu_count()), started before the
  loaded condition and stopped after it.

Writes DIR/report.md and DIR/results.json (default benchmarks/results/speed, a temporary folder
with --quick: 2 scenes at 64x48, a few samples, depth 3, seconds).
"""
import argparse
import datetime
import glob
import hashlib
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORKER = os.path.join(ROOT, "benchmarks", "bench", "speed_mitsuba.py")
RENDERERS = ["vulkan-auto", "vulkan-wavefront", "vulkan-fused", "cpu", "mitsuba"]
LABELS = {"vulkan-auto": "Vulkan auto", "vulkan-wavefront": "Vulkan wavefront", "vulkan-fused": "Vulkan fused",
          "cpu": "CPU backend", "mitsuba": "Mitsuba 3"}
MIXTRACE_ARGS = {"vulkan-auto": ["--backend", "vulkan", "--schedule", "auto"],
                 "vulkan-wavefront": ["--backend", "vulkan", "--schedule", "wavefront"],
                 "vulkan-fused": ["--backend", "vulkan", "--schedule", "fused"],
                 "cpu": ["--backend", "cpu"]}


def log(msg):
    print(f"[speed {time.strftime('%H:%M:%S')}] {msg}", flush=True)


# --- set-up: Mitsuba in a virtual environment ---------------------------------------------------

def newest_llvm():
    """The newest libLLVM >= 16 in the system's library folders, or None."""
    best = None
    for path in glob.glob("/usr/lib/*/libLLVM*.so*") + glob.glob("/usr/lib/libLLVM*.so*"):
        digits = "".join(c if c.isdigit() else " " for c in os.path.basename(path)).split()
        if digits and int(digits[0]) >= 16 and (best is None or int(digits[0]) > best[0]):
            best = (int(digits[0]), path)
    return best[1] if best else None


def worker_env():
    env = dict(os.environ)
    llvm = newest_llvm()
    if llvm and "DRJIT_LIBLLVM_PATH" not in env:
        env["DRJIT_LIBLLVM_PATH"] = llvm
    return env


def probe(python, variant):
    r = subprocess.run([python, WORKER, "probe", "--variant", variant], capture_output=True, text=True,
                       env=worker_env())
    if r.returncode == 0:
        return json.loads(r.stdout.strip().splitlines()[-1]), None
    return None, (r.stderr.strip().splitlines() or ["exit status %d" % r.returncode])[0][:200]


def setup_mitsuba(venv):
    """Returns (python, variant, info, notes)."""
    notes = []
    python = os.path.join(venv, "bin", "python")
    if not os.path.exists(python):
        log(f"set-up: creating the virtual environment {venv} (python3 -m venv)")
        subprocess.run([sys.executable if os.path.basename(sys.executable).startswith("python3") else "python3",
                        "-m", "venv", venv], check=True)
    if subprocess.run([python, "-c", "import mitsuba, numpy"], capture_output=True).returncode != 0:
        log(f"set-up: installing mitsuba and numpy into {venv} from the Python package registry (pip)")
        subprocess.run([os.path.join(venv, "bin", "pip"), "install", "-q", "mitsuba", "numpy"], check=True)
    info, err = probe(python, "llvm_ad_rgb")
    if info is None and newest_llvm() is None and os.geteuid() == 0 and shutil.which("apt-get"):
        log(f"set-up: Mitsuba's llvm_ad_rgb failed ({err}); Dr.Jit needs LLVM >= 16: "
            "apt-get install libllvm19 (beside Mesa's LLVM, which stays in use for lavapipe)")
        r = subprocess.run(["apt-get", "install", "-y", "-q", "--no-install-recommends", "libllvm19"],
                           env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))
        if r.returncode != 0:
            subprocess.run(["apt-get", "update", "-q"], env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))
            subprocess.run(["apt-get", "install", "-y", "-q", "--no-install-recommends", "libllvm19"],
                           env=dict(os.environ, DEBIAN_FRONTEND="noninteractive"))
        notes.append("installed Debian's libllvm19 for Dr.Jit's LLVM backend")
        info, err = probe(python, "llvm_ad_rgb")
    if info is not None:
        return python, "llvm_ad_rgb", info, notes
    notes.append(f"Mitsuba's llvm_ad_rgb variant could not render here ({err}): measured with scalar_rgb "
                 "(Mitsuba's multithreaded scalar renderer, slower than its LLVM backend)")
    log("set-up: " + notes[-1])
    info, err = probe(python, "scalar_rgb")
    if info is None:
        raise SystemExit(f"speed: Mitsuba does not run from {venv}: {err}")
    return python, "scalar_rgb", info, notes


# --- measurements -------------------------------------------------------------------------------

class Runner:
    def __init__(self, args, python, variant, work):
        self.args, self.python, self.variant, self.work = args, python, variant, work

    def mixtrace(self, renderer, scene, spp, tag):
        a = self.args
        out = os.path.join(self.work, f"{tag}.exr")
        cmd = [a.binary, "render", scene, *MIXTRACE_ARGS[renderer], "--method", "pt-power",
               "--width", str(a.width), "--height", str(a.height), "--max-depth", str(a.max_depth),
               "--spp", str(spp), "--stats", out + ".json", "-q", "--no-png", "--out", out]
        subprocess.run(cmd, check=True)
        with open(out + ".json") as f:
            s = json.load(f)
        return {"spp": s["spp"], "samples_per_second": s["samples_per_second"], "seconds": s["render_seconds"],
                "device": s.get("device"), "schedule": s.get("schedule"), "image": out}

    def mitsuba(self, mode, scene, spp=None, tag=None):
        a = self.args
        cmd = [self.python, WORKER, mode, scene, "--variant", self.variant, "--width", str(a.width),
               "--height", str(a.height), "--max-depth", str(a.max_depth)]
        if mode == "calibrate":
            cmd += ["--seconds", str(a.seconds)]
        else:
            cmd += ["--spp", str(spp), "--out", os.path.join(self.work, f"{tag}.exr")]
        r = subprocess.run(cmd, capture_output=True, text=True, env=worker_env())
        if r.returncode != 0:
            raise SystemExit(f"speed: Mitsuba failed on {scene}:\n{r.stderr[-2000:]}")
        d = json.loads(r.stdout.strip().splitlines()[-1])
        if mode != "calibrate":
            d["seconds"] = d.pop("render_seconds")
            d["image"] = os.path.join(self.work, f"{tag}.exr")
        return d

    def measure(self, renderer, scene, spp, tag):
        if renderer == "mitsuba":
            return self.mitsuba("render", scene, spp, tag)
        return self.mixtrace(renderer, scene, spp, tag)

    def calibrate(self, renderer, scene):
        """Samples per pixel for about --seconds of rendering on this scene."""
        pixels = self.args.width * self.args.height
        if renderer == "mitsuba":
            d = self.mitsuba("calibrate", scene)
            rate = d["samples_per_second"]
        else:
            pilot = 1 if self.args.quick else (2 if renderer.startswith("vulkan") else 4)
            m = self.mixtrace(renderer, scene, pilot, "calibrate")
            if m["seconds"] < self.args.seconds / 4:  # too short to time reliably: once more, about half as long
                pilot = max(pilot + 1, int(pilot * self.args.seconds / 2 / max(m["seconds"], 1e-3)))
                m = self.mixtrace(renderer, scene, pilot, "calibrate")
            rate = m["samples_per_second"]
        return max(1, int(round(self.args.seconds * rate / pixels))), rate


class Load:
    """One CPU-bound process per core."""
    def __init__(self, n):
        self.procs = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(n)]

    def stop(self):
        for p in self.procs:
            p.terminate()
        for p in self.procs:
            p.wait()


def machine(binary):
    cpu = platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    devices = subprocess.run([binary, "--list-devices"], capture_output=True, text=True).stdout.strip()
    version = subprocess.run([binary, "--version"], capture_output=True, text=True).stdout.strip()
    mem = ""
    try:
        with open("/proc/meminfo") as f:
            mem = f"{int(f.readline().split()[1]) / 2**20:.0f} GiB"
    except (OSError, ValueError, IndexError):
        pass
    with open(binary, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    head = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    return {"cpu": cpu, "cores": os.cpu_count(), "memory": mem, "vulkan_devices": devices, "renderer": version,
            "binary_sha256": digest, "git_head": head.stdout.strip(), "os": platform.platform()}


def image_means(python, paths):
    r = subprocess.run([python, WORKER, "means", *paths], capture_output=True, text=True, env=worker_env())
    if r.returncode != 0:
        return {}
    return json.loads(r.stdout.strip().splitlines()[-1])


# --- report -------------------------------------------------------------------------------------

def fmt_rate(v):
    return f"{v / 1e6:.3f}" if v else "-"


def fmt_ratio(a, b):
    return f"{a / b:.2f}x" if a and b else "-"


def best(runs):
    return max((r["samples_per_second"] for r in runs), default=None)


def spread(runs):
    v = [r["samples_per_second"] for r in runs]
    return f"{min(v) / 1e6:.3f}-{max(v) / 1e6:.3f}" if len(v) > 1 else (f"{v[0] / 1e6:.3f}" if v else "-")


def condition_table(res, cond):
    lines = ["| scene | " + " | ".join(LABELS[r] for r in RENDERERS) +
             " | Vulkan auto / CPU | Vulkan (best schedule) / CPU | Vulkan auto / Mitsuba | "
             "Vulkan (best schedule) / Mitsuba | CPU / Mitsuba |",
             "|---|" + "---|" * (len(RENDERERS) + 5)]
    for scene, per in res["measurements"][cond].items():
        b = {r: best(per[r]) for r in RENDERERS}
        vk = max(b["vulkan-wavefront"] or 0, b["vulkan-fused"] or 0) or None
        which = "wf" if (b["vulkan-wavefront"] or 0) >= (b["vulkan-fused"] or 0) else "fused"
        chose = {"wavefront": "wf", "fused": "fused"}.get(next((m.get("schedule") for m in per["vulkan-auto"]), None), "?")
        lines.append(f"| {scene} | " + " | ".join(fmt_rate(b[r]) for r in RENDERERS) +
                     f" | {fmt_ratio(b['vulkan-auto'], b['cpu'])} ({chose}) | {fmt_ratio(vk, b['cpu'])} ({which}) | "
                     f"{fmt_ratio(b['vulkan-auto'], b['mitsuba'])} | {fmt_ratio(vk, b['mitsuba'])} | "
                     f"{fmt_ratio(b['cpu'], b['mitsuba'])} |")
    return lines


def spread_table(res, cond):
    lines = ["| scene | " + " | ".join(f"{LABELS[r]} (spp)" for r in RENDERERS) + " |",
             "|---|" + "---|" * len(RENDERERS)]
    for scene, per in res["measurements"][cond].items():
        lines.append(f"| {scene} | " + " | ".join(f"{spread(per[r])} ({res['spp'][scene][r]})" for r in RENDERERS) + " |")
    return lines


def load_table(res):
    lines = ["| scene | " + " | ".join(LABELS[r] for r in RENDERERS) + " |", "|---|" + "---|" * len(RENDERERS)]
    idle, loaded = res["measurements"]["idle"], res["measurements"]["loaded"]
    for scene in idle:
        lines.append(f"| {scene} | " + " | ".join(fmt_ratio(best(loaded[scene][r]), best(idle[scene][r]))
                                                 for r in RENDERERS) + " |")
    return lines


def loadavg_range(res, cond):
    v = [m["loadavg_1min"] for per in res["measurements"][cond].values() for runs in per.values() for m in runs]
    return f"{min(v):.2f}-{max(v):.2f}" if v else "-"


def markdown(res):
    m, c = res["machine"], res["config"]
    mi = res["mitsuba"]
    out = ["# Speed: mixtrace (Vulkan on lavapipe, each schedule; CPU backend) against Mitsuba 3", "",
           f"Measured {res['date']} on {m['cpu']} ({m['cores']} cores, {m['memory']}), {m['os']}.",
           f"Vulkan device: {res['device']}. {m['renderer']} (binary sha256 {m.get('binary_sha256', '?')[:12]}, "
           f"repository at {m.get('git_head', '?')}).",
           f"Mitsuba {mi['mitsuba']} (Dr.Jit {mi['drjit']}), variant `{mi['variant']}`"
           + (f", LLVM {mi['llvm']}" if mi.get("llvm") else "") + ".",
           f"Command: `{res['command']}` ({res['minutes']:.1f} min).", "",
           f"Images {c['width']}x{c['height']}, max depth {c['max_depth']}, mixtrace `--method pt-power` "
           "(one light sample by power and one BSDF sample per vertex, MIS), Mitsuba `path` (one emitter "
           "sample and one BSDF sample per vertex, MIS) with Russian roulette off (rr_depth 1000), "
           "`principled` BSDFs from the glTF factors and textures as the speed stand-in for the glTF BRDF. "
           f"Samples per pixel calibrated per scene and renderer for about {c['seconds']} s on the idle machine "
           f"(the same counts under load); best of {c['repeat']} interleaved runs, in M samples/s "
           "(width x height x spp / render time; set-up, scene loading and Mitsuba's JIT warm-up excluded).", "",
           f"Load average (1 min) before starting: {res['loadavg_before'][0]:.2f} "
           f"({', '.join(f'{x:.2f}' for x in res['loadavg_before'])} over 1/5/15 min): the machine is shared, "
           "so the idle condition is not an idle machine; the renderers were interleaved so that each saw the "
           "same background load.", ""]
    for n in res["notes"]:
        out += [f"Note: {n}", ""]
    out += [f"## Idle (no competing process; load average during the runs {loadavg_range(res, 'idle')})", ""]
    out += condition_table(res, "idle") + [""]
    if res["measurements"].get("loaded"):
        out += [f"## Under load ({res['load_processes']} competing CPU-bound processes, one per core; load average "
                f"during the runs {loadavg_range(res, 'loaded')})", ""]
        out += condition_table(res, "loaded") + [""]
        out += ["## Throughput under load / idle (best against best)", ""] + load_table(res) + [""]
        out += ["The competing processes share the cores with whatever else runs on the machine: on a machine "
                "that is already busy (compare the load averages of the two conditions) they take a smaller "
                "share than on an idle one, and the ratio says less about the renderers than about the background.", ""]
    out += ["## All runs (M samples/s, min-max over the repeats; spp per render)", "", "### Idle", ""]
    out += spread_table(res, "idle") + [""]
    if res["measurements"].get("loaded"):
        out += ["### Under load", ""] + spread_table(res, "loaded") + [""]
    out += ["## Image means (idle, last run; not an accuracy comparison)", "",
            "Mean over the image and the three channels, to show that every renderer drew the scene "
            "(a gross mismatch such as a black image would show here). Mitsuba's `principled` is not "
            "the glTF BRDF (it adds a specular lobe to diffuse materials, among others), so its means "
            "differ by some per cent.", "",
            "| scene | " + " | ".join(LABELS[r] for r in RENDERERS) + " |", "|---|" + "---|" * len(RENDERERS)]
    for scene, per in res["means"].items():
        out.append(f"| {scene} | " + " | ".join(f"{per[r]:.4f}" if per.get(r) is not None else "-"
                                               for r in RENDERERS) + " |")
    return "\n".join(out) + "\n"


# --- main ---------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="2 scenes at 64x48, depth 3, a few samples: seconds")
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "mixtrace"))
    ap.add_argument("--out", help="output folder (default benchmarks/results/speed; a temporary one with --quick)")
    ap.add_argument("--venv", default="/tmp/mi", help="virtual environment holding Mitsuba (created if missing)")
    ap.add_argument("--scenes", help="comma-separated scene files under scenes/ (default: all shipped scenes)")
    ap.add_argument("--seconds", type=float, help="target render time per measurement on the idle machine (default 3)")
    ap.add_argument("--repeat", type=int, help="runs per scene, renderer and condition (default 3; best reported)")
    ap.add_argument("--no-load", action="store_true", help="skip the measurements under load")
    args = ap.parse_args()
    started = time.time()
    loadavg_before = os.getloadavg()
    command = " ".join(["python3", "benchmarks/speed.py"] + sys.argv[1:])

    if args.quick:
        args.width, args.height, args.max_depth = 64, 48, 3
        args.seconds = args.seconds or 0.3
        args.repeat = args.repeat or 1
        default_scenes = ["cornell_box.gltf", "textured.glb"]
    else:
        args.width, args.height, args.max_depth = 320, 240, 5
        args.seconds = args.seconds or 3.0
        args.repeat = args.repeat or 3
        default_scenes = sorted(os.path.basename(p) for p in glob.glob(os.path.join(ROOT, "scenes", "*.gltf")) +
                                glob.glob(os.path.join(ROOT, "scenes", "*.glb")))
    scenes = args.scenes.split(",") if args.scenes else default_scenes
    args.out = args.out or (tempfile.mkdtemp(prefix="mixtrace-speed-quick-") if args.quick
                            else os.path.join(ROOT, "benchmarks", "results", "speed"))
    os.makedirs(args.out, exist_ok=True)
    if not os.path.exists(args.binary):
        raise SystemExit(f"speed: no mixtrace binary at {args.binary} (build first: bash scripts/setup.sh)")
    # A private copy: a rebuild while this runs must not change the binary under measurement.
    bindir = tempfile.mkdtemp(prefix="mixtrace-speed-bin-")
    shutil.copy2(args.binary, os.path.join(bindir, "mixtrace"))
    args.binary = os.path.join(bindir, "mixtrace")
    if "XDG_RUNTIME_DIR" not in os.environ:
        os.environ["XDG_RUNTIME_DIR"] = f"/tmp/xdg-runtime-{os.getuid()}"
        os.makedirs(os.environ["XDG_RUNTIME_DIR"], mode=0o700, exist_ok=True)

    log(f"load average before starting: {loadavg_before}")
    python, variant, mi_info, notes = setup_mitsuba(args.venv)
    log(f"Mitsuba {mi_info['mitsuba']}, variant {variant}" + (f", LLVM {mi_info['llvm']}" if mi_info.get("llvm") else ""))
    work = tempfile.mkdtemp(prefix="mixtrace-speed-")
    runner = Runner(args, python, variant, work)
    scene_paths = {s: os.path.join(ROOT, "scenes", s) for s in scenes}

    res = {"date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"), "command": command,
           "machine": machine(args.binary), "loadavg_before": list(loadavg_before), "notes": notes,
           "config": {"width": args.width, "height": args.height, "max_depth": args.max_depth,
                      "method": "pt-power", "seconds": args.seconds, "repeat": args.repeat, "scenes": scenes},
           "mitsuba": mi_info, "spp": {}, "calibration_samples_per_second": {}, "measurements": {}, "means": {}}

    log("calibrating the sample counts (idle)")
    for s in scenes:
        res["spp"][s], res["calibration_samples_per_second"][s] = {}, {}
        for r in RENDERERS:
            spp, rate = runner.calibrate(r, scene_paths[s])
            res["spp"][s][r], res["calibration_samples_per_second"][s][r] = spp, rate
        log(f"  {s}: " + ", ".join(f"{r} {res['spp'][s][r]} spp" for r in RENDERERS))

    conditions = ["idle"] + ([] if args.no_load else ["loaded"])
    res["load_processes"] = os.cpu_count()
    last_images = {}
    for cond in conditions:
        load = None
        if cond == "loaded":
            log(f"starting {os.cpu_count()} competing CPU-bound processes")
            load = Load(os.cpu_count())
            time.sleep(2)
        try:
            res["measurements"][cond] = {s: {r: [] for r in RENDERERS} for s in scenes}
            for rep in range(args.repeat):
                for si, s in enumerate(scenes):
                    k = (rep + si) % len(RENDERERS)
                    for r in RENDERERS[k:] + RENDERERS[:k]:
                        la = os.getloadavg()[0]
                        m = runner.measure(r, scene_paths[s], res["spp"][s][r], f"{cond}-{os.path.splitext(s)[0]}-{r}")
                        m["loadavg_1min"], m["repeat"] = la, rep
                        if cond == "idle":
                            last_images.setdefault(s, {})[r] = m["image"]
                        if r.startswith("vulkan") and m.get("device"):
                            res["device"] = m["device"]
                        res["measurements"][cond][s][r].append(m)
                        log(f"  {cond} #{rep + 1} {s} {r}: {m['samples_per_second'] / 1e6:.3f} M samples/s "
                            f"({m['spp']} spp, {m['seconds']:.2f} s, load {la:.2f})")
        finally:
            if load:
                load.stop()
                log("stopped the competing processes")

    paths = [p for per in last_images.values() for p in per.values()]
    means = image_means(python, paths)
    for s, per in last_images.items():
        res["means"][s] = {r: (sum(means[p]) / 3 if p in means else None) for r, p in per.items()}
    res.setdefault("device", "?")
    res["loadavg_after"] = list(os.getloadavg())
    res["minutes"] = (time.time() - started) / 60
    for cond in res["measurements"].values():
        for per in cond.values():
            for runs in per.values():
                for m in runs:
                    m.pop("image", None)
    with open(os.path.join(args.out, "results.json"), "w") as f:
        json.dump(res, f, indent=1)
    with open(os.path.join(args.out, "report.md"), "w") as f:
        f.write(markdown(res))
    shutil.rmtree(work, ignore_errors=True)
    shutil.rmtree(bindir, ignore_errors=True)
    log(f"wrote {args.out}/report.md and results.json ({res['minutes']:.1f} min)")
    print(markdown(res))


if __name__ == "__main__":
    main()
