#!/usr/bin/env bash
# Installs from Debian's packages what one purpose needs (only what is missing), then configures
# and builds, in Release, only what that purpose runs. Idempotent: a second run installs nothing
# and rebuilds nothing that is up to date.
#
#   bash scripts/setup.sh [render]    the mixtrace binary alone (scripts/quickstart.sh)
#   bash scripts/setup.sh benchmarks  the binary, plus numpy and matplotlib (scripts/benchmark.sh)
#   bash scripts/setup.sh tests       everything the test suite needs; builds the binary and
#                                     every test program (scripts/test.sh, .ci/run)
#   bash scripts/setup.sh PURPOSE --plan   only print what it would install and build (for
#                                     tests/scripts/setup_plan_test.sh); changes nothing
set -euo pipefail
cd "$(dirname "$0")/.."
purpose=${1:-render}
plan_only=false; [ "${2:-}" = --plan ] && plan_only=true

# What building and running the binary needs (CMakeLists.txt's find_package calls, the headers
# host/ includes, and lavapipe to render on without a GPU). g++ rather than build-essential:
# the build uses Ninja, so make, dpkg-dev and perl would be downloaded for nothing.
RENDER_PACKAGES=(
  g++ cmake ninja-build
  libvulkan-dev mesa-vulkan-drivers glslang-tools
  libglfw3-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
  libopenexr-dev libimath-dev
)
# The benchmark suite's tables and charts (benchmarks/suite.py runs Debian's python3).
BENCHMARK_PACKAGES=(python3 python3-numpy python3-matplotlib)
# Only the tests: GoogleTest, the validation layer (the tests require zero validation errors),
# a virtual X display for the viewer's test, Python for the scene check and the benchmark's
# quick run (tests/CMakeLists.txt).
TEST_PACKAGES=(libgtest-dev vulkan-validationlayers xvfb xauth "${BENCHMARK_PACKAGES[@]}")

case "$purpose" in
  render)     packages=("${RENDER_PACKAGES[@]}");                          targets=(--target mixtrace) ;;
  benchmarks) packages=("${RENDER_PACKAGES[@]}" "${BENCHMARK_PACKAGES[@]}"); targets=(--target mixtrace) ;;
  tests)      packages=("${RENDER_PACKAGES[@]}" "${TEST_PACKAGES[@]}");      targets=() ;;
  *) echo "setup: error: unknown purpose '$purpose' (render, benchmarks or tests)" >&2; exit 2 ;;
esac
if $plan_only; then
  echo "packages: ${packages[*]}"
  echo "targets: ${targets[*]:-all}"
  exit 0
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  apt_start=$SECONDS
  echo "setup: updating Debian's package lists (apt-get update)"
  $SUDO apt-get update -q | grep --line-buffered -E '^(Get|Fetched|Err|W:|E:)' || true
  # What apt will fetch, dependencies included: the number and the download size.
  count=$(apt-get install -s --no-install-recommends "${missing[@]}" | grep -c '^Inst ' || true)
  megabytes=$(apt-get install --print-uris -qq --no-install-recommends "${missing[@]}" |
              awk '{ bytes += $3 } END { printf "%d", bytes / 1e6 + 0.5 }')
  echo "setup: installing $count packages (about $megabytes MB to download, typically 1-3 minutes)" \
       "for ${missing[*]}"
  # apt's own per-package lines (download, set-up), without its unpacking and trigger chatter.
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" |
    grep --line-buffered -E '^(Get:|Fetched|Setting up|E:|W:)' || true
  # grep's status is not apt's: check that everything did get installed.
  for p in "${missing[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
      { echo "setup: error: apt-get did not install $p (see its messages above)" >&2; exit 1; }
  done
  echo "setup: $count packages installed in $((SECONDS - apt_start)) s"
fi

# Some Vulkan loaders and layers want a runtime directory even when headless.
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp/xdg-runtime-$(id -u)}
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"

# The tests purpose insists on GoogleTest; the others configure without it (CMakeLists.txt).
require_tests=OFF; [ "$purpose" = tests ] && require_tests=ON
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DMIXTRACE_REQUIRE_TESTS=$require_tests >/dev/null
if [ "$purpose" = tests ]; then
  echo "setup: building mixtrace and every test program (the first time about 3-10 minutes on 2 cores)"
else
  echo "setup: building mixtrace (the first time about 1-3 minutes on 2 cores)"
fi
build_start=$SECONDS
cmake --build build "${targets[@]}"
echo "setup: build done in $((SECONDS - build_start)) s"
