#!/usr/bin/env bash
# The README's first command: install what is missing, build in Release, render the default
# scene (scenes/cornell_box.gltf) to cornell_box.exr and cornell_box.png in the current directory.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/scripts/setup.sh"
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/xdg-runtime-$(id -u)}
"$root/build/mixtrace" render --out cornell_box.exr --stats cornell_box.json "$@"
