#!/usr/bin/env bash
# What loading a scene's meshes costs: two vkraycast binaries (before and after a change to
# mesh loading, e.g. assimp in its own process: docs/design.md §5) parse the same scenes,
# interleaved (A, B, A, B, ...), ROUNDS processes each, rendering a 16x12 frame on the CPU
# so that parsing dominates. Per scene: the median parse_ms (--stats-json: reading the
# scene and its meshes, wall time), the median CPU time of the whole process tree (user +
# system, the importer process included: /usr/bin/time counts the children it waits
# for) and the median peak RSS of the largest process in it. Only figures from one run of
# this script are compared with each other (the machine is shared and noisy).
# Usage: tools/bench_mesh_import.sh BIN_A BIN_B SCENE...   Env: ROUNDS (5)
set -euo pipefail
cd "$(dirname "$0")/.."
a=$1 b=$2
shift 2
rounds=${ROUNDS:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
echo "A: $a"
echo "B: $b"
echo "$(nproc) cores; $rounds processes each; medians"
echo
echo "| scene | A parse ms | B parse ms | A CPU s (tree) | B CPU s (tree) | A peak RSS MiB | B peak RSS MiB |"
echo "|---|---|---|---|---|---|---|"
for s in "$@"; do
  : >"$work/A.txt"
  : >"$work/B.txt"
  for ((r = 0; r < rounds; r++)); do
    for which in A B; do
      bin=$a
      [[ $which == B ]] && bin=$b
      if ! /usr/bin/time -f "%U %S %M" -o "$work/time.txt" "$bin" render "$s" -o "$work/out.exr" --width 16 \
        --height 12 --backend cpu --quiet --allow-outside-paths --stats-json "$work/st.json" 2>"$work/err"; then
        cat "$work/err" >&2
        exit 1
      fi
      read -r user sys rss <"$work/time.txt"
      echo "$(num parse_ms "$work/st.json") $(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }') $((rss / 1024))" \
        >>"$work/$which.txt"
    done
  done
  col() { awk -v c="$2" '{print $c}' "$work/$1.txt" | median; }
  printf "| %s | %.1f | %.1f | %.2f | %.2f | %.0f | %.0f |\n" "$(basename "$s")" "$(col A 1)" "$(col B 1)" \
    "$(col A 2)" "$(col B 2)" "$(col A 3)" "$(col B 3)"
done
