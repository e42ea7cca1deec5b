#!/usr/bin/env bash
# What a short command costs before and after the two start-up changes of issue 48's CI
# work: the image module's libraries loaded leaves first (vkraycast-image.deps,
# host/image/image_load.c) and the specialization constants applied on the host
# (--spec-constants, host/gpu/spirv_specialize.h). Four ways, interleaved, ROUNDS
# processes each (the machine is shared and noisy: compare only within one run):
#   before     a copy of the build without vkraycast-image.deps, --spec-constants driver
#   list       the build, --spec-constants driver
#   host       a copy without the list, --spec-constants host
#   after      the build as it is (both)
# Prints per command the medians of CPU seconds (user + system), wall seconds and, for
# GPU renders, pipeline_ms. Validation is on, as in the test suite.
# Usage: tools/bench_startup.sh [BUILD_DIR]   (default build/)   Env: ROUNDS (7)
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
rounds=${ROUNDS:-7}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
as_the_tests
# The copy without the list: the binary finds the module (and the importer) beside itself.
mkdir "$work/nolist"
cp "$build/vkraycast" "$build/vkraycast-image.so" "$build/vkraycast-mesh-import" "$work/nolist/"
[[ -f $build/vkraycast-image.deps ]] || { echo "no $build/vkraycast-image.deps: build first" >&2; exit 1; }
"$build/vkraycast" render scenes/shadows.json -o "$work/cmp.png" -q
commands=(
  "gpu8|render scenes/shadows.json -o $work/o.png --width 8 --height 8 -q"
  "showcase|render scenes/showcase.json -o $work/o.png -q"
  "cpu8|render scenes/shadows.json -o $work/o.png --width 8 --height 8 -q --backend cpu"
  "compare|compare $work/cmp.png $work/cmp.png"
)
ways=(before list host after)
printf "%s cores, %s processes each, medians; CPU and wall in s\n\n" "$(nproc)" "$rounds"
echo "| command | way | CPU | wall | pipeline_ms |"
echo "|---|---|---|---|---|"
for entry in "${commands[@]}"; do
  name=${entry%%|*} args=${entry#*|}
  for w in "${ways[@]}"; do : >"$work/$w.txt"; done
  for ((r = 0; r < rounds; r++)); do
    for w in "${ways[@]}"; do
      bin=$build/vkraycast spec=()
      [[ $w == before || $w == host ]] && bin=$work/nolist/vkraycast
      [[ $args == render* && $args != *"--backend cpu"* ]] && {
        spec=(--spec-constants host)
        [[ $w == before || $w == list ]] && spec=(--spec-constants driver)
        spec+=(--stats-json "$work/st.json")
      }
      # shellcheck disable=SC2086
      /usr/bin/time -f "%U %S %e" -o "$work/time" "$bin" $args "${spec[@]}" >/dev/null
      p=-
      [[ ${#spec[@]} -gt 0 ]] && p=$(num pipeline_ms "$work/st.json")
      echo "$(awk '{print $1 + $2, $3}' "$work/time") $p" >>"$work/$w.txt"
    done
  done
  for w in "${ways[@]}"; do
    col() { awk -v c="$1" '{print $c}' "$work/$w.txt" | median; }
    pm=-
    [[ $(head -c1 <(awk '{print $3}' "$work/$w.txt")) != - ]] && pm=$(printf "%.0f" "$(col 3)")
    printf "| %s | %s | %.2f | %.2f | %s |\n" "$name" "$w" "$(col 1)" "$(col 2)" "$pm"
  done
done
