#!/usr/bin/env bash
# The README's first command: install what the binary needs (only what is missing), build the
# mixtrace target alone in Release (not the tests: scripts/test.sh builds those), and render the
# default scene (scenes/cornell_box.gltf) to cornell_box.exr, .png and .json in the current
# directory. Arguments go to `mixtrace render`, e.g. --backend cpu or --spp 64.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
start=$SECONDS
bash "$root/scripts/setup.sh" render
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/xdg-runtime-$(id -u)}
echo "quickstart: rendering scenes/cornell_box.gltf (a few seconds)"
"$root/build/mixtrace" render --out cornell_box.exr --stats cornell_box.json "$@"
echo "quickstart: done in $((SECONDS - start)) s: cornell_box.exr (float RGB), cornell_box.png (preview), cornell_box.json (statistics)"
