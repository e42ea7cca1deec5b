#!/usr/bin/env bash
# Why our Embree yardstick measures slower than a harness written as Embree's tutorials
# write one (docs/performance.md, "Two Embree harnesses"): tools/bench_embree.c on the
# sphere grid and the 100k and 1M-triangle meshes of tools/bench_vs_embree.sh, 1024x768,
# 1 spp, primary + shadow rays, 2 point lights, with its speed knobs turned on one at a
# time, beside the GPU path (lavapipe, f32) in the same run. Mrays/s counts primary and
# shadow rays; each figure is the median over ROUNDS rounds (one process each, the
# variants alternating) of each process's median frame (frames 2..FRAMES).
# Usage: tools/bench_embree_harness.sh   (FRAMES=6, ROUNDS=3, THREADS=nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/bench_embree_env.sh
for n in 100000 1000000; do
  build/gen_mesh $n "$work/mesh$n.ply" >/dev/null
  tools/mesh_scene.sh "$work/mesh$n.ply" >"$work/mesh$n.json"
done
tools/gen_sphere_grid.sh 64 >"$work/spheres4096.json"
variants=(
  "reference shading (as bench_vs_embree.sh)|--shading reference"
  "lambert shading|--shading lambert"
  "lambert, shadow packets|--shading lambert --shadow-packets 1"
  "lambert, shadow packets, coherent|--shading lambert --shadow-packets 1 --coherent 1"
  "the same, build quality high|--shading lambert --shadow-packets 1 --coherent 1 --quality high"
  "reference shading, shadow packets, coherent|--shading reference --shadow-packets 1 --coherent 1"
)
echo "Machine: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1), $(nproc) cores; $threads threads."
echo "Command: tools/bench_embree_harness.sh (FRAMES=$frames, ROUNDS=$rounds). 1024x768, 1 spp."
echo
echo "| scene | harness | Embree 1-ray Mrays/s | Embree 8-packet Mrays/s | GPU f32 Mrays/s | GPU / Embree-8 |"
echo "|---|---|---|---|---|---|"
size="--width 1024 --height 768"
for name in spheres4096 mesh100000 mesh1000000; do
  s=$work/$name.json
  : >"$work/g.txt"
  for v in "${!variants[@]}"; do : >"$work/e1-$v.txt" && : >"$work/e8-$v.txt"; done
  for ((r = 0; r < rounds; r++)); do
    build/vkraycast render "$s" --allow-outside-paths -o "$work/o.png" $size --spp 1 --precision f32 --repeat "$frames" \
      --quiet --stats-json "$work/gpu.json" 2>/dev/null
    num mrays_per_s "$work/gpu.json" >>"$work/g.txt"
    for v in "${!variants[@]}"; do
      # shellcheck disable=SC2086
      build/bench_embree "$s" $size --repeat "$frames" --threads "$threads" ${variants[$v]#*|} >"$work/e.json"
      num embree_single_mrays_per_s "$work/e.json" >>"$work/e1-$v.txt"
      num embree_packet8_mrays_per_s "$work/e.json" >>"$work/e8-$v.txt"
    done
  done
  g=$(median <"$work/g.txt")
  for v in "${!variants[@]}"; do
    e1=$(median <"$work/e1-$v.txt") e8=$(median <"$work/e8-$v.txt")
    printf "| %s | %s | %.2f | %.2f | %.2f | %.2f |\n" "$name" "${variants[$v]%%|*}" "$e1" "$e8" "$g" \
      "$(awk -v a="$g" -v b="$e8" 'BEGIN{print a/b}')"
  done
done
