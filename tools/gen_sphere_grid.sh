#!/usr/bin/env bash
# Writes a benchmark scene with an N x N grid of spheres on a floor, two point lights.
# Usage: tools/gen_sphere_grid.sh N > scene.json
set -euo pipefail
n=${1:?usage: gen_sphere_grid.sh N}
awk -v n="$n" 'BEGIN {
  printf "{\n  \"image\": { \"width\": 256, \"height\": 192 },\n"
  printf "  \"camera\": { \"eye\": [0, %g, %g], \"look_at\": [0, 0, 0], \"fov_y_deg\": 50 },\n", n * 0.9, n * 1.3
  printf "  \"background\": [0.05, 0.05, 0.08],\n"
  printf "  \"materials\": { \"floor\": { \"ambient\": [0.05, 0.05, 0.05], \"diffuse\": [0.6, 0.6, 0.6] },\n"
  printf "    \"ball\": { \"ambient\": [0.05, 0.02, 0.02], \"diffuse\": [0.7, 0.3, 0.2], \"specular\": [0.5, 0.5, 0.5], \"shininess\": 30 } },\n"
  printf "  \"lights\": [ { \"type\": \"point\", \"position\": [%g, %g, %g], \"intensity\": [%g, %g, %g] },\n", -n, n, n, n*n*3, n*n*3, n*n*3
  printf "              { \"type\": \"point\", \"position\": [%g, %g, %g], \"intensity\": [%g, %g, %g] } ],\n", n, n, 0, n*n, n*n, n*n
  printf "  \"objects\": [\n"
  printf "    { \"type\": \"triangle\", \"vertices\": [[%g, 0, %g], [%g, 0, %g], [%g, 0, %g]], \"material\": \"floor\" },\n", -n, -n, -n, n, n, n
  printf "    { \"type\": \"triangle\", \"vertices\": [[%g, 0, %g], [%g, 0, %g], [%g, 0, %g]], \"material\": \"floor\" }", -n, -n, n, n, n, -n
  for (i = 0; i < n; i++) for (j = 0; j < n; j++)
    printf ",\n    { \"type\": \"sphere\", \"center\": [%g, 0.4, %g], \"radius\": 0.4, \"material\": \"ball\" }", i - (n - 1) / 2, j - (n - 1) / 2
  printf "\n  ]\n}\n"
}'
