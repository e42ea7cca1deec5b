#!/usr/bin/env bash
# The specialized pipeline against the generic one (docs/performance.md): for a
# sphere-only, a mesh and a mixed scene, pipeline creation (shader module + compute
# pipeline, where lavapipe compiles), the first frame, the steady-state frame (median of
# frames 2..N, GPU timestamps) with one tile and with the adaptive tiles, and the
# process's CPU time. ROUNDS separate processes per configuration, generic and specialized
# interleaved in each round; each figure is the median over the rounds.
#   tools/bench_pipeline.sh            (ROUNDS=5 REPEAT=5 SIZE=320x240 SPP=4)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$root/build/vkraycast
[[ -x $bin ]] || { echo "build first (tools/demo.sh)" >&2; exit 2; }
rounds=${ROUNDS:-5} repeat=${REPEAT:-5} size=${SIZE:-320x240} spp=${SPP:-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
num() { sed -n "s/^[[:space:]]*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
scenes=("spheres|$root/tests/extremes/scenes/S21_many_spheres_D2.json"
        "mesh|$root/scenes/mesh.json"
        "mixed|$root/scenes/showcase.json"
        "quadrics|$root/scenes/quadrics.json"
        "csg|$root/scenes/csg.json")
common=(--width "${size%x*}" --height "${size#*x}" --spp "$spp" --repeat "$repeat" --quiet)
echo "| scene | objects | pipeline | tiles | pipeline ms | first frame ms | steady frame ms | dispatches | CPU ms (process) |"
echo "|---|---|---|---|---|---|---|---|---|"
for entry in "${scenes[@]}"; do
  name=${entry%%|*} scene=${entry#*|}
  for tiles in one adaptive; do
    tile_opt=()
    [[ $tiles == one ]] && tile_opt=(--tile 1024)
    for r in $(seq "$rounds"); do
      for p in specialized generic; do
        "$bin" render "$scene" -o "$work/x.exr" --pipeline "$p" --allow-outside-paths "${common[@]}" "${tile_opt[@]}" \
          --stats-json "$work/$name.$tiles.$p.$r.json"
      done
    done
    for p in specialized generic; do
      j=("$work/$name.$tiles.$p".*.json)
      objects=$(( $(num spheres "${j[0]}") + $(num triangles "${j[0]}") + $(num quadrics "${j[0]}") + $(num composites "${j[0]}") ))
      col() { for f in "${j[@]}"; do num "$1" "$f"; done | median; }
      printf '| %s | %s | %s | %s | %.0f | %.0f | %.1f | %s | %.0f |\n' "$name" "$objects" "$p" "$tiles" \
        "$(col pipeline_ms)" "$(col first_frame_ms)" "$(col render_ms)" "$(col dispatches)" "$(col cpu_ms)"
    done
  done
done
