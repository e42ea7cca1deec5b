#!/usr/bin/env bash
# Prints a scene around a mesh file: 1024x768, framed from the mesh's bounding box, a floor
# under it, two point lights (the benchmark scenes of tools/bench_vs_embree.sh and
# tools/bench_shards.sh). Needs build/bench_embree (for --bbox).
#   tools/mesh_scene.sh MESH_FILE > scene.json
set -euo pipefail
cd "$(dirname "$0")/.."
read -r x0 y0 z0 x1 y1 z1 _ < <(build/bench_embree --bbox "$1")
awk -v x0="$x0" -v y0="$y0" -v z0="$z0" -v x1="$x1" -v y1="$y1" -v z1="$z1" -v file="$1" 'BEGIN {
  cx = (x0 + x1) / 2; cy = (y0 + y1) / 2; cz = (z0 + z1) / 2
  r = sqrt((x1 - x0) ^ 2 + (y1 - y0) ^ 2 + (z1 - z0) ^ 2) / 2; d = r / sin(3.14159265 / 9) * 1.05
  printf "{ \"image\": { \"width\": 1024, \"height\": 768 },\n"
  printf "  \"camera\": { \"eye\": [%g, %g, %g], \"look_at\": [%g, %g, %g], \"fov_y_deg\": 40 },\n",
    cx + 0.6 * d, cy + 0.45 * d, cz + 0.66 * d, cx, cy, cz
  printf "  \"materials\": { \"m\": { \"ambient\": [0.05, 0.05, 0.05], \"diffuse\": [0.7, 0.6, 0.5], \"specular\": [0.3, 0.3, 0.3], \"shininess\": 30 },\n"
  printf "                 \"floor\": { \"ambient\": [0.05, 0.05, 0.05], \"diffuse\": [0.6, 0.6, 0.6] } },\n"
  printf "  \"lights\": [ { \"type\": \"point\", \"position\": [%g, %g, %g], \"intensity\": [%g, %g, %g] },\n",
    cx - 2 * r, cy + 3 * r, cz + 2 * r, 10 * r * r, 10 * r * r, 10 * r * r
  printf "              { \"type\": \"point\", \"position\": [%g, %g, %g], \"intensity\": [%g, %g, %g] } ],\n",
    cx + 3 * r, cy + 1.5 * r, cz - r, 4 * r * r, 4 * r * r, 4 * r * r
  printf "  \"objects\": [ { \"type\": \"mesh\", \"file\": \"%s\", \"material\": \"m\" },\n", file
  f = 4 * r
  printf "    { \"type\": \"triangle\", \"vertices\": [[%g, %g, %g], [%g, %g, %g], [%g, %g, %g]], \"material\": \"floor\" },\n",
    cx - f, y0, cz - f, cx - f, y0, cz + f, cx + f, y0, cz + f
  printf "    { \"type\": \"triangle\", \"vertices\": [[%g, %g, %g], [%g, %g, %g], [%g, %g, %g]], \"material\": \"floor\" } ] }\n",
    cx - f, y0, cz - f, cx + f, y0, cz + f, cx + f, y0, cz - f
}'
