#!/usr/bin/env bash
# Benchmark against Intel Embree 3 (issue 4): procedural meshes of about 1k, 100k and 1M
# triangles, 4096 spheres, and real meshes from Debian's assimp-testmodels, at 1024x768,
# 1 spp, 2 point lights with shadows, on each vkraycast backend and with Embree (single
# rays and 8-wide packets, tuned as "Two Embree harnesses" in docs/performance.md says)
# from the same packed scene, in one run. GPU and CPU reference
# side by side in f32 (the same arithmetic), the CPU reference in f64 (its default) and
# the GPU at its default precision (auto) beside them. Prints one markdown table.
# Mrays/s counts primary + shadow rays; steady state = median of frames 2..N. The three
# figures the ratios compare (GPU f32, CPU f32, Embree) are medians over ROUNDS rounds of
# one process each, alternating, so a burst of load on this shared machine moves one
# round, not a column.
# Usage: tools/bench_vs_embree.sh   (FRAMES=6, ROUNDS=3, THREADS=nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/bench_embree_env.sh

# A scene around a mesh file (tools/mesh_scene.sh).
mesh_scene() { tools/mesh_scene.sh "$2" >"$work/$1.json"; }

for n in 1000 100000 1000000; do
  build/gen_mesh $n "$work/mesh$n.ply" >/dev/null
  mesh_scene "mesh$n" "$work/mesh$n.ply"
done
tools/gen_sphere_grid.sh 64 >"$work/spheres4096.json"
mesh_scene wuson /usr/share/assimp/models/OBJ/WusonOBJ.obj
mesh_scene spider /usr/share/assimp/models/OBJ/spider.obj
mesh_scene engine /usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb

cpu_model=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
echo "Machine: $cpu_model, $(nproc) cores; $(build/vkraycast devices | sed -n 2p | cut -c7-46 | sed 's/ *$//'); Embree $(pkg-config --modversion embree3 2>/dev/null || echo 3); $threads threads for the CPU renderers."
echo "Command: tools/bench_vs_embree.sh (FRAMES=$frames, ROUNDS=$rounds). 1024x768, 1 spp, primary + shadow rays."
echo
echo "| scene | objects | BVH build ms | GPU first frame ms, cold / warm cache | GPU f32 Mrays/s | CPU f32 Mrays/s | GPU / CPU | CPU f64 Mrays/s | Embree 1-ray | Embree 8-packet (lambert, shadow packets, coherent) | GPU / Embree-8 | GPU Mrays/s at defaults (precision) | peak RSS MiB (GPU) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
size="--width 1024 --height 768 --spp 1"
for name in mesh1000 mesh100000 mesh1000000 spheres4096 wuson spider engine; do
  s=$work/$name.json
  # Cold: an empty cache folder (Mesa's shader cache and vkraycast's pipeline cache both
  # live under XDG_CACHE_HOME); warm: the same folder after one run.
  export XDG_CACHE_HOME=$work/cache-$name
  build/vkraycast render "$s" --allow-outside-paths -o "$work/o.png" $size --precision f32 --quiet --stats-json "$work/cold.json" 2>/dev/null
  build/vkraycast render "$s" --allow-outside-paths -o "$work/o.png" $size --precision f32 --quiet --stats-json "$work/warm.json" 2>/dev/null
  : >"$work/g.txt"
  : >"$work/c.txt"
  : >"$work/e1.txt"
  : >"$work/e8.txt"
  for ((r = 0; r < rounds; r++)); do
    build/vkraycast render "$s" --allow-outside-paths -o "$work/$name.png" $size --precision f32 --repeat "$frames" --quiet \
      --stats-json "$work/gpu.json" 2>/dev/null
    build/vkraycast render "$s" --allow-outside-paths -o "$work/o.png" $size --precision f32 --repeat "$frames" --backend cpu \
      --threads "$threads" --quiet --stats-json "$work/cpu.json" 2>/dev/null
    # Embree at its best (docs/performance.md, "Two Embree harnesses"): the cheapest
    # shading both sides share, shadow rays in packets, coherent primary packets.
    build/bench_embree "$s" --width 1024 --height 768 --repeat "$frames" --threads "$threads" \
      --shading lambert --shadow-packets 1 --coherent 1 >"$work/embree.json"
    num mrays_per_s "$work/gpu.json" >>"$work/g.txt"
    num mrays_per_s "$work/cpu.json" >>"$work/c.txt"
    num embree_single_mrays_per_s "$work/embree.json" >>"$work/e1.txt"
    num embree_packet8_mrays_per_s "$work/embree.json" >>"$work/e8.txt"
  done
  build/vkraycast render "$s" --allow-outside-paths -o "$work/o.png" $size --repeat "$frames" --quiet --stats-json "$work/gpu_auto.json" 2>/dev/null
  build/vkraycast render "$s" --allow-outside-paths -o "$work/o.png" $size --repeat "$frames" --backend cpu --threads "$threads" --quiet \
    --stats-json "$work/cpu64.json" 2>/dev/null
  unset XDG_CACHE_HOME
  objects=$(( $(num spheres "$work/gpu.json") + $(num triangles "$work/gpu.json") ))
  g=$(median <"$work/g.txt") c=$(median <"$work/c.txt") c64=$(num mrays_per_s "$work/cpu64.json")
  ga=$(num mrays_per_s "$work/gpu_auto.json") pa=$(sed -n 's/.*"precision":[[:space:]]*"\([a-z0-9]*\)".*/\1/p' "$work/gpu_auto.json")
  e1=$(median <"$work/e1.txt") e8=$(median <"$work/e8.txt")
  printf "| %s | %s | %.0f | %.0f / %.0f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f (%s) | %.0f |\n" "$name" "$objects" \
    "$(num bvh_build_ms "$work/gpu.json")" "$(num first_frame_ms "$work/cold.json")" "$(num first_frame_ms "$work/warm.json")" \
    "$g" "$c" "$(awk -v a="$g" -v b="$c" 'BEGIN{print a/b}')" "$c64" "$e1" "$e8" \
    "$(awk -v a="$g" -v b="$e8" 'BEGIN{print a/b}')" "$ga" "$pa" "$(num peak_rss_mib "$work/gpu.json")"
done
