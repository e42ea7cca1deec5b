#!/usr/bin/env bash
# What a shard costs beyond its pixels (docs/cluster.md): for each scene, the wall and CPU
# time of a whole-frame render process, and of a process that renders one pixel
# (--region 0,0,1,1): process start, parsing, the BVH, the device, the pipeline (warm
# cache), the upload, one dispatch and the write. The pixels' own time is the difference.
# N shards of the frame spend N overheads on top of it; the overhead passes 10 % of the
# total at N = pixels / (9 x overhead). Medians of ROUNDS processes.
#   tools/bench_shards.sh [SCENE...]   (default: scenes/*.json and a 1M-triangle mesh)
# Env: ROUNDS (3); ARGS: render options for every run (say "--width 1920 --height 1080
# --spp 16" for frames the size of a farm's).
set -euo pipefail
cd "$(dirname "$0")/.."
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
rounds=${ROUNDS:-3}
read -r -a extra <<<"${ARGS:-}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenes=("$@")
if ((${#scenes[@]} == 0)); then
  cmake --build build --target bench_embree gen_mesh -j"$(nproc)" >&2
  build/gen_mesh 1000000 "$work/mesh1000000.ply" >/dev/null
  tools/mesh_scene.sh "$work/mesh1000000.ply" >"$work/mesh1000000.json"
  scenes=(scenes/*.json "$work/mesh1000000.json")
fi
source tools/bench_common.sh
# run OUT_PREFIX render-args...: appends "wall_ms cpu_ms" of one process
run() {
  local out=$1
  shift
  local t0 t1
  t0=$(date +%s%N)
  build/vkraycast render "$@" "${extra[@]}" --quiet --allow-outside-paths -o "$work/o.exr" --stats-json "$work/s.json"
  t1=$(date +%s%N)
  echo "$(((t1 - t0) / 1000000)) $(num cpu_ms "$work/s.json")" >>"$out"
}
echo "device: $(build/vkraycast devices | sed -n 2p | cut -c7-46 | sed 's/ *$//'), $(nproc) cores; medians of $rounds processes${ARGS:+; $ARGS}"
echo
echo "| scene | size, spp | whole frame: wall ms (CPU ms) | one pixel: wall ms (CPU ms) | pixels' wall ms | shards at 10 % overhead |"
echo "|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  name=$(basename "$s" .json)
  build/vkraycast render "$s" "${extra[@]}" --quiet --allow-outside-paths -o "$work/o.exr" --stats-json "$work/s.json" # warm caches
  size="$(num width "$work/s.json")x$(num height "$work/s.json"), $(num samples_per_pixel "$work/s.json")"
  : >"$work/whole" && : >"$work/pixel"
  for ((r = 0; r < rounds; r++)); do
    run "$work/whole" "$s"
    run "$work/pixel" "$s" --region 0,0,1,1
  done
  ww=$(cut -d' ' -f1 "$work/whole" | median) wc=$(cut -d' ' -f2 "$work/whole" | median)
  pw=$(cut -d' ' -f1 "$work/pixel" | median) pc=$(cut -d' ' -f2 "$work/pixel" | median)
  awk -v n="$name" -v sz="$size" -v ww="$ww" -v wc="$wc" -v pw="$pw" -v pc="$pc" 'BEGIN {
    px = ww - pw; if (px < 0) px = 0
    printf "| %s | %s | %.0f (%.0f) | %.0f (%.0f) | %.0f | %s |\n", n, sz, ww, wc, pw, pc, px,
      (px > 9 * pw ? sprintf("%d", px / (9 * pw)) : "1 (the overhead is over 10 % already)") }'
done
