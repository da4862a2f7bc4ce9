#!/usr/bin/env python3
"""benchmarks/ab.py cannot rot: on a tiny render it alternates the Vulkan wavefront and the CPU
backend, and its figures must be the stats JSONs' (one rate per repeat and variant, the first
variant's ratios exactly 1, the others' the quotients of the rates, GPU pass times only where
Vulkan ran); a variant whose render fails must end it with a one-line error and a non-zero exit.

    ab_check.py REPO_ROOT MIXTRACE_BINARY OUT_DIR
"""
import json
import os
import subprocess
import sys

root, binary, out = sys.argv[1:4]
os.makedirs(out, exist_ok=True)
ab = [sys.executable, os.path.join(root, "benchmarks", "ab.py"), "cornell_box.gltf",
      "--spp", "1", "--reps", "2", "--width", "32", "--height", "24"]
result = os.path.join(out, "ab.json")
p = subprocess.run(ab + ["--variant", f"wf:{binary}:--schedule wavefront", "--variant", f"cpu:{binary}:--backend cpu",
                         "--json", result], capture_output=True, text=True)
failures = []
if p.returncode != 0:
    sys.exit(f"ab.py failed (exit {p.returncode}): {p.stderr.strip()}")
d = json.load(open(result))
wf, cpu = d["variants"]
for v in (wf, cpu):
    if len(v["rates"]) != 2 or not all(r > 0 for r in v["rates"]):
        failures.append(f"{v['label']}: expected 2 positive rates, got {v['rates']}")
if wf["ratios"] != [1.0, 1.0]:
    failures.append(f"the first variant's ratios to itself are {wf['ratios']}")
expected = sorted(a / b for a, b in zip(cpu["rates"], wf["rates"]))
if any(abs(a - b) > 1e-12 for a, b in zip(cpu["ratios"], expected)):
    failures.append(f"cpu ratios {cpu['ratios']} are not the rates' quotients {expected}")
if "intersect" not in wf["pass_ms"] or cpu["pass_ms"]:
    failures.append(f"GPU pass times: wavefront {sorted(wf['pass_ms'])}, cpu {sorted(cpu['pass_ms'])}")
for label in ("wf", "cpu"):
    if f"{label}: median" not in p.stdout:
        failures.append(f"the report has no line for {label}:\n{p.stdout}")

bad = subprocess.run(ab + ["--reps", "1", "--variant", f"a:{binary}:--no-such-option", "--variant", f"b:{binary}"],
                     capture_output=True, text=True)
if bad.returncode == 0 or "ab: variant a: mixtrace render failed" not in bad.stderr or "Traceback" in bad.stderr:
    failures.append(f"a failing variant: exit {bad.returncode}, stderr {bad.stderr.strip()!r}")

if failures:
    sys.exit("ab_check: " + "\n".join(failures))
print("ab_check: ok")
