#!/usr/bin/env bash
# What creating the pipeline costs a short GPU render, two builds side by side (finding 11
# of docs/performance.md, "Process start-up"): a 32 x 24 render of each scene, the ways
# interleaved, ROUNDS processes each (the machine is shared and noisy: compare only within
# one run), validation on as in the test suite, Mesa's shader cache warm:
#   A          BUILD_A as it is
#   B-nocache  BUILD_B with VKRAYCAST_PIPELINE_CACHE=0 (every specialization made anew)
#   B          BUILD_B as it is (the specialized module read from its file)
# Prints per scene and way the medians of CPU seconds (user + system), pipeline_ms and
# specialize_ms, and checks that the three give the same image and decisions.
# Usage: tools/bench_spec_cache.sh BUILD_A BUILD_B SCENE...   Env: ROUNDS (7)
set -euo pipefail
cd "$(dirname "$0")/.."
a=$(realpath "$1") b=$(realpath "$2")
shift 2
rounds=${ROUNDS:-7}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
as_the_tests
export XDG_CACHE_HOME=$work/cache MESA_SHADER_CACHE_DIR=$work/mesa
ways=(A B-nocache B)
run() { # WAY SCENE OUT [args]
  local w=$1 scene=$2 out=$3 bin=$b/vkraycast
  shift 3
  [[ $w == A ]] && bin=$a/vkraycast
  local env=()
  [[ $w == B-nocache ]] && env=(VKRAYCAST_PIPELINE_CACHE=0)
  env "${env[@]}" /usr/bin/time -f "%U %S" -o "$work/time" "$bin" render "$scene" -o "$out" --width 32 --height 24 \
    -q "$@"
}
printf "%s cores, %s processes each, medians; CPU in s\n\n" "$(nproc)" "$rounds"
echo "| scene | way | CPU | pipeline_ms | specialize_ms |"
echo "|---|---|---|---|---|"
for scene in "$@"; do
  name=$(basename "$scene" .json)
  for w in "${ways[@]}"; do # the images to compare, then the caches warmed for the rounds
    run "$w" "$scene" "$work/$w.exr" --aov "$work/$w.aov.exr"
    run "$w" "$scene" "$work/o.exr"
    : >"$work/$w.txt"
  done
  for w in B-nocache B; do
    for f in exr aov.exr; do
      "$b/vkraycast" compare "$work/A.$f" "$work/$w.$f" --fail 0 --hardfail 0 >/dev/null ||
        { echo "$name: $w's $f differs from A's" >&2; exit 1; }
    done
  done
  for ((r = 0; r < rounds; r++)); do
    for w in "${ways[@]}"; do
      run "$w" "$scene" "$work/o.exr" --stats-json "$work/st.json"
      echo "$(awk '{print $1 + $2}' "$work/time") $(num pipeline_ms "$work/st.json") $(num specialize_ms "$work/st.json")" \
        >>"$work/$w.txt"
    done
  done
  for w in "${ways[@]}"; do
    col() { awk -v c="$1" '{print $c}' "$work/$w.txt" | median; }
    printf "| %s | %s | %.2f | %.0f | %.0f |\n" "$name" "$w" "$(col 1)" "$(col 2)" "$(col 3)"
  done
done
