#!/usr/bin/env bash
# The README's first command builds and installs only what the binary needs (issue 11, point 14):
# scripts/setup.sh's render purpose (what scripts/quickstart.sh runs) builds the mixtrace target
# alone and installs no test-only package, while the tests purpose (scripts/test.sh, .ci/run)
# installs everything the tests need and builds every target. Reads the plan that
# `setup.sh PURPOSE --plan` prints; installs and builds nothing.
# Usage: setup_plan_test.sh SOURCE_DIR
set -uo pipefail
src=${1:?source directory}
failures=0
fail() { echo "setup_plan_test: FAIL: $*"; failures=$((failures + 1)); }

# What only the tests (or the benchmarks) use, and what building the binary needs
# (CMakeLists.txt's find_package calls and the renderer's headers; lavapipe to render on).
TEST_ONLY=(libgtest-dev vulkan-validationlayers xvfb xauth python3-numpy python3-matplotlib)
BINARY_NEEDS=(g++ cmake ninja-build libvulkan-dev mesa-vulkan-drivers glslang-tools libglfw3-dev libglm-dev
              libtinygltf-dev nlohmann-json3-dev libstb-dev libopenexr-dev libimath-dev)

plan() { bash "$src/scripts/setup.sh" "$1" --plan; }
packages_of() { sed -n 's/^packages: //p' <<<"$1" | tr ' ' '\n'; }
targets_of() { sed -n 's/^targets: //p' <<<"$1"; }
has() { grep -qx -- "$2" <<<"$1"; }

render=$(plan render) || fail "setup.sh render --plan failed"
tests=$(plan tests) || fail "setup.sh tests --plan failed"
benchmarks=$(plan benchmarks) || fail "setup.sh benchmarks --plan failed"

[ "$(targets_of "$render")" = "--target mixtrace" ] || fail "render builds '$(targets_of "$render")', not the mixtrace target alone"
[ "$(targets_of "$benchmarks")" = "--target mixtrace" ] || fail "benchmarks builds '$(targets_of "$benchmarks")', not the mixtrace target alone"
[ "$(targets_of "$tests")" = "all" ] || fail "tests builds '$(targets_of "$tests")', not every target"

for p in "${TEST_ONLY[@]}"; do
  has "$(packages_of "$render")" "$p" && fail "render installs the test-only package $p"
  has "$(packages_of "$tests")" "$p" || fail "tests does not install $p"
done
for p in "${BINARY_NEEDS[@]}"; do
  for purpose in render benchmarks tests; do
    has "$(packages_of "${!purpose}")" "$p" || fail "$purpose does not install $p, which the binary needs"
  done
done
for p in python3-numpy python3-matplotlib; do
  has "$(packages_of "$benchmarks")" "$p" || fail "benchmarks does not install $p"
done
bash "$src/scripts/setup.sh" no-such-purpose --plan >/dev/null 2>&1 && fail "an unknown purpose is accepted"

# The README's two commands use the purposes above.
grep -q 'scripts/setup.sh" render' "$src/scripts/quickstart.sh" || fail "quickstart.sh does not run setup.sh render"
grep -q 'scripts/setup.sh tests' "$src/scripts/test.sh" || fail "test.sh does not run setup.sh tests"

[ "$failures" -eq 0 ] && echo "setup_plan_test: ok"
exit $(( failures > 0 ))
