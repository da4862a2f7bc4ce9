#!/usr/bin/env bash
# Installs what is missing, builds in Release and runs the whole test suite (CTest) on lavapipe.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/xdg-runtime-$(id -u)}
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
cd build
# The long statistical variant runs on request: (cd build && ctest -L long)
ctest --output-on-failure -j2 -LE long "$@"
