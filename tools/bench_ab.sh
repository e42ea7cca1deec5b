#!/usr/bin/env bash
# Before/after benchmark: two vkraycast binaries render the same scenes, interleaved
# (A, B, A, B, ...), ROUNDS processes each, at the scene's own settings unless ARGS says
# otherwise. Per scene: the median over processes of the steady-state frame (wall ms per
# frame over frames 2..FRAMES, from --repeat), the first frame, process CPU ms, the
# dispatch count, and the process's wall ms (start-up and the last frame's write included:
# with FRAMES=1, what a user rendering one image waits for). The machine is shared and noisy: only figures from one run of this
# script are compared with each other.
# Usage: tools/bench_ab.sh BIN_A BIN_B [SCENE...]   (default: scenes/*.json)
# Env: ROUNDS (5), FRAMES (3), ARGS (extra render options for both, e.g. "--width 320
# --height 200"), ARGS_A and ARGS_B (for one side only: one binary against itself with
# other options, e.g. ARGS_B="--tile 4096"), EXT (exr: the output's format; png for the
# 8-bit encoding)
set -euo pipefail
cd "$(dirname "$0")/.."
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
a=$1 b=$2
shift 2
rounds=${ROUNDS:-5} frames=${FRAMES:-3}
scenes=("$@")
((${#scenes[@]})) || scenes=(scenes/*.json)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
echo "A: $a ${ARGS_A:-}"
echo "B: $b ${ARGS_B:-}"
echo "$(nproc) cores; $rounds processes each, --repeat $frames${ARGS:+, $ARGS}; medians"
echo
echo "| scene | A ms/frame | B ms/frame | B/A | A first frame | B first frame | A CPU ms | B CPU ms | A dispatches | B dispatches | A process ms | B process ms |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  : >"$work/A.txt"
  : >"$work/B.txt"
  for ((r = 0; r < rounds; r++)); do
    for which in A B; do
      bin=$a extra=${ARGS_A:-}
      [[ $which == B ]] && bin=$b extra=${ARGS_B:-}
      t0=$(date +%s%N)
      # shellcheck disable=SC2086
      "$bin" render "$s" -o "$work/out.${EXT:-exr}" --repeat "$frames" --quiet --allow-outside-paths ${ARGS:-} $extra --stats-json "$work/st.json"
      process=$((($(date +%s%N) - t0) / 1000))
      wall=$(num render_wall_ms "$work/st.json") first=$(num first_frame_ms "$work/st.json")
      # render_wall_ms is the median of frames 2..N (stats.h); the first frame is apart.
      # The CPU backend has no dispatches: "-" keeps the columns in place.
      dispatches=$(num dispatches "$work/st.json")
      echo "$wall $first $(num cpu_ms "$work/st.json") ${dispatches:--} $process" >>"$work/$which.txt"
    done
  done
  col() { awk -v c="$2" '{print $c}' "$work/$1.txt" | median; }
  printf "| %s | %.1f | %.1f | %.2f | %.1f | %.1f | %.0f | %.0f | %s | %s | %.1f | %.1f |\n" "$(basename "$s" .json)" \
    "$(col A 1)" "$(col B 1)" "$(awk -v x="$(col A 1)" -v y="$(col B 1)" 'BEGIN { print y / x }')" \
    "$(col A 2)" "$(col B 2)" "$(col A 3)" "$(col B 3)" "$(col A 4)" "$(col B 4)" \
    "$(awk -v u="$(col A 5)" 'BEGIN { print u / 1000 }')" "$(awk -v u="$(col B 5)" 'BEGIN { print u / 1000 }')"
done
