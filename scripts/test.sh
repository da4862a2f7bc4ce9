#!/usr/bin/env bash
# The README's second command (and .ci/run's): install everything the tests need (only what is
# missing), build the binary and every test program in Release, run the whole suite (CTest) on
# lavapipe. Arguments go to ctest, e.g. -R render_cli.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh tests
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/xdg-runtime-$(id -u)}
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
cd build
# The long statistical variant runs on request: (cd build && ctest -L long)
ctest --output-on-failure -j2 -LE long "$@"
