#!/usr/bin/env bash
# The benchmark suite in one command: installs what is missing (Debian packages, including
# python3-matplotlib and python3-numpy for the charts), builds in Release, then runs
# benchmarks/suite.py, which writes benchmarks/results/ (report.md, results.json, charts).
# Arguments go to the suite, e.g. --quick (seconds; what CI runs) or --scenes veach_mis.gltf.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh benchmarks
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/xdg-runtime-$(id -u)}
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
# Debian's interpreter, which has the packages above (a python3 earlier on PATH may not).
exec /usr/bin/python3 benchmarks/suite.py "$@"
