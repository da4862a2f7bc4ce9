#!/usr/bin/env bash
# The bit-identity check for refactors: a change that must not alter behaviour must leave every
# image the same, bit for bit, for the same seed and settings.
#
#   scripts/bit_identity.sh record BASE_BINARY DIR   # before: render everything into DIR
#   scripts/bit_identity.sh check  NEW_BINARY  DIR   # after: render again, compare with DIR
#
# "Everything" is every shipped scene (scenes/) with every method on both backends, at 32x24,
# 64 spp (at 16 the control variates of some scenes' cells are not solved yet), seed 7, with
# --variance, so the standard-error channels are compared too. Only pixels are compared (R, G, B,
# standardError.R/G/B, by tests/tools/exr_pixels_equal): header attributes such as renderSeconds
# differ from run to run by design.
#
# `record` renders each case twice and compares the two. A case whose renders differ is not
# deterministic run to run (the GPU's CMS statistics are sums of atomic additions, whose order
# depends on thread timing); it is marked so in DIR/manifest.txt, and `check` asks of it only
# that the images be equal within round-off (relMSE below 1e-8: such reorderings measured 1e-14
# at most, and the two backends, which differ by round-off alone, up to 6e-11; two methods'
# images of one scene differ by 1e-3 and more) or agree in `mixtrace compare`'s per-pixel
# statistical test, and says which. Two equal renders do not prove a case deterministic, so when a case differs in
# `check`, the new binary renders it once more: if those two differ as well, it is judged so too.
# Every line of the manifest carries a hash of the pixel data, to compare records by eye.
#
# `check` prints one line per case (identical / differs, with the first differing value) and exits
# 0 when every deterministic case is identical and every other one is equal within round-off or
# agrees in the statistical test.
#
# A build's binary is build/mixtrace. To check a refactor against its base revision, build the base
# in a second worktree (git worktree add /tmp/base BASE_REV; cmake -S /tmp/base -B /tmp/base/build
# ...), record with its binary, then check with the new one. BASE_BINARY and NEW_BINARY may be the
# same binary: that checks determinism.
#
# Environment: BIT_IDENTITY_SCENES, BIT_IDENTITY_METHODS, BIT_IDENTITY_BACKENDS (space-separated)
# narrow the set (both modes must see the same set); EXR_PIXELS_EQUAL is the comparison tool
# (default: build/tests/exr_pixels_equal).
set -euo pipefail

usage() {
  echo "usage: $0 record|check MIXTRACE_BINARY DIR" >&2
  exit 2
}
[[ $# -eq 3 ]] || usage
mode=$1
binary=$(realpath "$2")
dir=$3
[[ $mode == record || $mode == check ]] || usage
[[ -x $binary ]] || { echo "$0: not an executable: $2" >&2; exit 2; }

root=$(cd "$(dirname "$0")/.." && pwd)
tool=${EXR_PIXELS_EQUAL:-$root/build/tests/exr_pixels_equal}
[[ -x $tool ]] || { echo "$0: no comparison tool at $tool (build target exr_pixels_equal, or set EXR_PIXELS_EQUAL)" >&2; exit 2; }
scenes=${BIT_IDENTITY_SCENES:-"cornell_box.gltf veach_mis.gltf many_lights.gltf indirect_rgb.gltf textured.glb punctual.gltf"}
methods=${BIT_IDENTITY_METHODS:-"pt-uniform pt-power learned cv cms"}
backends=${BIT_IDENTITY_BACKENDS:-"vulkan cpu"}
settings=(--width 32 --height 24 --spp 64 --seed 7 --variance -q --no-png)
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}

render() {  # scene method backend out.exr
  "$binary" render "$root/scenes/$1" --method "$2" --backend "$3" "${settings[@]}" --out "$4"
}

case_name() { echo "${1%.*}__$2__$3"; }  # one file name per case: scene__method__backend

start=$SECONDS
if [[ $mode == record ]]; then
  mkdir -p "$dir"
  manifest=$dir/manifest.txt
  {
    echo "# bit_identity.sh record: $("$binary" --version 2>&1 | head -1), $(sha256sum "$binary" | cut -c1-16)"
    echo "# settings: ${settings[*]}"
    echo "# scene method backend pixel-hash run-to-run"
  } >"$manifest"
  for scene in $scenes; do
    for method in $methods; do
      for backend in $backends; do
        name=$(case_name "$scene" "$method" "$backend")
        render "$scene" "$method" "$backend" "$dir/$name.exr"
        render "$scene" "$method" "$backend" "$dir/$name.again.exr"
        if "$tool" "$dir/$name.exr" "$dir/$name.again.exr" >/dev/null; then
          determinism=deterministic
        else
          determinism=nondeterministic
        fi
        rm -f "$dir/$name.again.exr"
        line="$scene $method $backend $("$tool" --hash "$dir/$name.exr") $determinism"
        echo "$line" >>"$manifest"
        echo "$line"
      done
    done
  done
  echo "recorded $(grep -vc '^#' "$manifest") cases in $dir in $((SECONDS - start)) s" \
       "($(grep -c ' nondeterministic$' "$manifest" || true) not deterministic run to run)"
  exit 0
fi

manifest=$dir/manifest.txt
[[ -f $manifest ]] || { echo "$0: no $manifest: run '$0 record BASE_BINARY $dir' first" >&2; exit 2; }
new=$(mktemp -d "${TMPDIR:-/tmp}/bit_identity.XXXXXX")
trap 'rm -rf "$new"' EXIT
identical=0
failed=0
statistical=0
printf '%-18s %-11s %-7s %s\n' scene method backend result
for scene in $scenes; do
  for method in $methods; do
    for backend in $backends; do
      name=$(case_name "$scene" "$method" "$backend")
      recorded=$(awk -v s="$scene" -v m="$method" -v b="$backend" '$1 == s && $2 == m && $3 == b' "$manifest")
      if [[ -z $recorded ]]; then
        result="FAILED: not in the record"
        failed=$((failed + 1))
      else
        render "$scene" "$method" "$backend" "$new/$name.exr"
        if difference=$("$tool" "$new/$name.exr" "$dir/$name.exr" 2>&1); then
          result=identical
          identical=$((identical + 1))
        elif [[ $recorded == *" nondeterministic" ]] || {
               render "$scene" "$method" "$backend" "$new/$name.again.exr"
               ! "$tool" "$new/$name.exr" "$new/$name.again.exr" >/dev/null; }; then
          # Not deterministic run to run, so bit identity cannot be asked of it: the same seed
          # must still estimate the same image, up to the order of its floating-point additions.
          relmse=$("$binary" compare "$new/$name.exr" "$dir/$name.exr" --error-only | awk '{print $2}')
          verdict=$("$binary" compare "$new/$name.exr" "$dir/$name.exr" 2>&1) && agree=1 || agree=0
          if awk -v e="$relmse" 'BEGIN { exit !(e < 1e-8) }' || [[ $agree -eq 1 ]]; then
            statistical=$((statistical + 1))
            result="not deterministic run to run; relMSE $relmse; per-pixel test: ${verdict%%:*}"
          else
            result="FAILED: not deterministic run to run; relMSE $relmse; per-pixel test: $verdict"
            failed=$((failed + 1))
          fi
        else
          result="FAILED: differs: $(echo "$difference" | tr '\n' ';')"
          failed=$((failed + 1))
        fi
      fi
      printf '%-18s %-11s %-7s %s\n' "${scene%.*}" "$method" "$backend" "$result"
    done
  done
done
total=$((identical + failed + statistical))
echo "checked $total cases in $((SECONDS - start)) s: $identical identical, $statistical not deterministic run" \
     "to run but equal within round-off or agreeing per pixel, $failed failed"
[[ $failed -eq 0 ]]
