#!/usr/bin/env bash
# The test kernels (shaders/tests/*.comp) are not in the product: the binary's embedded-shader
# table names every product shader and none of the test kernels (each entry's name is a string
# in the binary). The product shaders' names are the control: they show the search can see.
# Usage: product_kernels_test.sh BINARY SOURCE_DIR
set -uo pipefail
binary=${1:?binary}
src=${2:?source directory}
failures=0
fail() { echo "product_kernels_test: FAIL: $*"; failures=$((failures + 1)); }
in_binary() { grep -qaF -- "$1" "$binary"; }

for kernel in "$src"/shaders/tests/*.comp; do
  name=$(basename "$kernel" .comp)
  in_binary "$name" && fail "the binary holds the test kernel $name"
done
for shader in "$src"/shaders/{wavefront,cms,viewer}/*.comp; do
  name=$(basename "$shader" .comp)
  in_binary "$name" || fail "the product shader $name is not found in the binary (is the check blind?)"
done
[ "$failures" -eq 0 ] && echo "product_kernels_test: no test kernel in $binary"
exit $((failures > 0))
