#!/usr/bin/env bash
# Benchmark: renders each scene on lavapipe with each kind of scene buffers (image, texel, storage),
# interleaved, ROUNDS rounds of `--repeat FRAMES`; reports the median over rounds of each
# process's steady-state render time (GPU timestamps, the median of frames 2..FRAMES), the
# wall time per frame, process CPU time, and Mrays/s (primary + shadow + reflection).
# Usage: tools/bench.sh [SCENE...]   (default: scenes/*.json and 4/16-sphere grids)
# Env: ROUNDS (3), FRAMES (6), SIZE ("--width 320 --height 200"), SPP (1).
set -euo pipefail
cd "$(dirname "$0")/.."
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
rounds=${ROUNDS:-3} frames=${FRAMES:-6} size=${SIZE---width 320 --height 200} spp=${SPP-1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenes=("$@")
if ((${#scenes[@]} == 0)); then
  for n in 4 16; do tools/gen_sphere_grid.sh $n >"$work/grid$n.json"; done
  scenes=(scenes/*.json "$work/grid4.json" "$work/grid16.json")
fi
num() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2"; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "device: $(build/vkraycast devices | sed -n 2p | cut -c7-46 | sed 's/ *$//'), $(nproc) cores; ${size:-scene size} ${spp:+--spp $spp}; $rounds rounds x --repeat $frames"
echo
echo "| scene | objects | buffers | render ms (GPU) | wall ms/frame | CPU ms (process) | Mrays/s |"
echo "|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  name=$(basename "$s" .json)
  for kind in image texel storage; do : >"$work/$kind.txt"; done
  for ((r = 0; r < rounds; r++)); do
    for kind in image texel storage; do
      build/vkraycast render "$s" -o "$work/out.exr" $size --repeat "$frames" --quiet --allow-outside-paths ${spp:+--spp "$spp"} \
        --scene-buffers "$kind" --stats-json "$work/st.json"
      echo "$(num render_ms "$work/st.json") $(num render_wall_ms "$work/st.json") $(num cpu_ms "$work/st.json") \
$(num mrays_per_s "$work/st.json") $(( $(num spheres "$work/st.json") + $(num triangles "$work/st.json") + $(num quadrics "$work/st.json") + $(num composites "$work/st.json") ))" >>"$work/$kind.txt"
    done
  done
  for kind in image texel storage; do
    col() { awk -v c="$1" '{print $c}' "$work/$kind.txt" | median; }
    printf "| %s | %s | %s | %.1f | %.1f | %.0f | %.2f |\n" "$name" "$(col 5)" "$kind" "$(col 1)" "$(col 2)" "$(col 3)" "$(col 4)"
  done
done
