#!/usr/bin/env bash
# Writes a benchmark scene of N small spheres scattered through a box in front of the
# camera, no floor, one point light, 640 x 480: the scene class where most primary rays
# pass between objects, which the eye buffer is for (docs/performance.md, "The eye
# buffer"). The same N and SEED give the same scene.
# Usage: tools/gen_sphere_cloud.sh N [SEED] > scene.json
set -euo pipefail
n=${1:?usage: gen_sphere_cloud.sh N [SEED]}
seed=${2:-7}
awk -v n="$n" -v seed="$seed" 'BEGIN {
  srand(seed)
  printf "{\n  \"image\": { \"width\": 640, \"height\": 480 },\n"
  printf "  \"camera\": { \"eye\": [0, 0, 110], \"look_at\": [0, 0, 0], \"fov_y_deg\": 50 },\n"
  printf "  \"background\": [0.05, 0.05, 0.08],\n"
  printf "  \"materials\": { \"ball\": { \"ambient\": [0.05, 0.02, 0.02], \"diffuse\": [0.7, 0.3, 0.2], \"specular\": [0.5, 0.5, 0.5], \"shininess\": 30 } },\n"
  printf "  \"lights\": [ { \"type\": \"point\", \"position\": [-64, 64, 64], \"intensity\": [12288, 12288, 12288] } ],\n"
  printf "  \"objects\": ["
  for (i = 0; i < n; i++)
    printf "%s\n    { \"type\": \"sphere\", \"center\": [%.3f, %.3f, %.3f], \"radius\": %.3f, \"material\": \"ball\" }", \
      i ? "," : "", -40 + 80 * rand(), -25 + 50 * rand(), -40 + 80 * rand(), 0.2 + 0.6 * rand()
  printf "\n  ]\n}\n"
}'
