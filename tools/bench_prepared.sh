#!/usr/bin/env bash
# What a prepared scene saves each shard (docs/cluster.md, "Prepared scenes"): for each
# scene, a process that renders one pixel (--region 0,0,1,1: the shard's fixed cost),
# parsed against `--prepared FILE.vkrs`, wall and CPU time, medians of ROUNDS processes run
# alternately; the time `prepare` takes once; the scene's bytes (the scene file and every
# file it reads) against the prepared file's; and whether the whole frame is the same
# image both ways (cmp of the PNGs).
#   tools/bench_prepared.sh [SCENE...]   (default: the showcase and a 1M-triangle mesh)
# Env: ROUNDS (5). The renders' warnings (the precision budget's) are left out.
set -euo pipefail
cd "$(dirname "$0")/.."
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
rounds=${ROUNDS:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
scenes=("$@")
if ((${#scenes[@]} == 0)); then
  cmake --build build --target bench_embree gen_mesh -j"$(nproc)" >&2
  build/gen_mesh 1000000 "$work/mesh1000000.ply" >/dev/null
  tools/mesh_scene.sh "$work/mesh1000000.ply" >"$work/mesh1000000.json"
  scenes=(scenes/showcase.json "$work/mesh1000000.json")
fi
vk=build/vkraycast
# run OUT render-args...: appends "wall_ms cpu_ms" of one process
run() {
  local out=$1 t0 t1
  shift
  t0=$(date +%s%N)
  "$vk" render "$@" --quiet --allow-outside-paths --stats-json "$work/s.json" 2>>"$work/stderr"
  t1=$(date +%s%N)
  echo "$(((t1 - t0) / 1000000)) $(num cpu_ms "$work/s.json")" >>"$out"
}
med() { cut -d' ' -f"$2" "$1" | median; }
echo "device: $($vk devices | sed -n 2p | cut -c7-46 | sed 's/ *$//'), $(nproc) cores; medians of $rounds processes"
echo
echo "| scene | prepare once: wall ms | scene bytes | .vkrs bytes | one pixel parsed: wall ms (CPU ms) | one pixel prepared: wall ms (CPU ms) | saved a shard | whole frame same |"
echo "|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  name=$(basename "$s" .json) vkrs=$work/$(basename "$s" .json).vkrs
  t0=$(date +%s%N)
  "$vk" prepare "$s" -o "$vkrs" --quiet --allow-outside-paths
  t1=$(date +%s%N)
  prep_ms=$(((t1 - t0) / 1000000))
  # The scene's bytes: the file and every file it read (the statistics do not list them;
  # the prepared file does, so ask a render for none and count the scene and its meshes).
  scene_bytes=$(stat -c %s "$s")
  while read -r f; do scene_bytes=$((scene_bytes + $(stat -c %s "$f"))); done < <(
    sed -n 's/.*"file": *"\([^"]*\)".*/\1/p' "$s" | while read -r f; do
      [[ $f == /* ]] && echo "$f" || echo "$(dirname "$s")/$f"
    done | sort -u)
  vkrs_bytes=$(stat -c %s "$vkrs")
  "$vk" render "$s" --prepared "$vkrs" --region 0,0,1,1 -o "$work/o.exr" --quiet 2>>"$work/stderr" # warm caches
  : >"$work/parsed" && : >"$work/prepared"
  for ((r = 0; r < rounds; r++)); do
    run "$work/parsed" "$s" --region 0,0,1,1 -o "$work/o.exr"
    run "$work/prepared" "$s" --prepared "$vkrs" --region 0,0,1,1 -o "$work/o.exr"
  done
  "$vk" render "$s" -o "$work/a.png" --quiet --allow-outside-paths 2>>"$work/stderr"
  "$vk" render "$s" --prepared "$vkrs" -o "$work/b.png" --quiet 2>>"$work/stderr"
  same=$(cmp -s "$work/a.png" "$work/b.png" && echo yes || echo NO)
  pw=$(med "$work/parsed" 1) pc=$(med "$work/parsed" 2) qw=$(med "$work/prepared" 1) qc=$(med "$work/prepared" 2)
  awk -v n="$name" -v p="$prep_ms" -v sb="$scene_bytes" -v vb="$vkrs_bytes" -v pw="$pw" -v pc="$pc" -v qw="$qw" \
    -v qc="$qc" -v same="$same" 'BEGIN {
    printf "| %s | %d | %d | %d | %.0f (%.0f) | %.0f (%.0f) | %.0f ms (%.1fx) | %s |\n", n, p, sb, vb, pw, pc, qw, qc,
      pw - qw, pw / qw, same }'
done
