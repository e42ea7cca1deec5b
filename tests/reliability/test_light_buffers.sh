#!/usr/bin/env bash
# Light buffers and the eye buffer change no decision (docs/numerics.md §9): every example
# scene, and scenes made to stress the cells (a light inside an object's box, a light on a
# surface, objects across the cube's face edges and corners, slivers seen edge-on from the
# light, a crowd of small occluders around the light, shadow rays from a plane beyond the
# buffer's reach; for the eye: a triangle through the eye's plane, a sphere behind it,
# sub-pixel objects on tile edges, objects past the image's edges, a parallel camera),
# render the same image and the same AOV decisions with both buffers on and both off, on the GPU in
# f32 and on the CPU reference in f64. The statistics must show the buffers were built and
# used cells of every kind where the scene has them.
# Usage: test_light_buffers.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"

# stress SEED -> a scene: two point lights among occluders (slivers in the lights' own
# planes, spheres on the cube's diagonals, a triangle whose box holds light 1, a grid of
# tiny triangles), over a floor plane and a receiving triangle, and a directional light,
# which has no buffer.
stress() {
  awk -v seed="$1" 'BEGIN {
    srand(seed)
    print "{ \"version\": 1, \"image\": { \"width\": 96, \"height\": 72, \"samples_per_pixel\": 2 },"
    print "  \"camera\": { \"eye\": [0.3, 2.2, 6], \"look_at\": [0, 0.6, 0], \"fov_y_deg\": 50 },"
    print "  \"materials\": { \"m\": { \"diffuse\": [0.7, 0.7, 0.7], \"specular\": [0.3, 0.3, 0.3], \"shininess\": 20 } },"
    print "  \"lights\": ["
    print "    { \"type\": \"point\", \"position\": [0, 1.5, 0], \"intensity\": [3, 3, 3] },"
    print "    { \"type\": \"point\", \"position\": [1.25, 0.75, -0.5], \"intensity\": [2, 2, 2] },"
    print "    { \"type\": \"directional\", \"direction\": [0.2, -1, -0.3], \"intensity\": [0.3, 0.3, 0.3] } ],"
    print "  \"objects\": ["
    print "    { \"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 1, 0], \"material\": \"m\" },"
    print "    { \"type\": \"triangle\", \"vertices\": [[-3, 0, -3], [3, 0, -3], [0, 4, -3]], \"material\": \"m\" },"
    # Its box holds light 1 (0, 1.5, 0): every cell of that light names it.
    print "    { \"type\": \"triangle\", \"vertices\": [[-0.6, 1.2, -0.3], [0.6, 1.2, -0.2], [0, 1.9, 0.3]], \"material\": \"m\" },"
    # A fine grid of 900 tiny triangles: the cells that see it hold more than a leaf can
    # (RC_LIGHT_BUFFER_LIST), so they name a subtree.
    for (i = 0; i < 30; i++)
      for (j = 0; j < 30; j++)
        printf "    { \"type\": \"triangle\", \"vertices\": [[%.4f, %.4f, -2], [%.4f, %.4f, -2], [%.4f, %.4f, -2]], \"material\": \"m\" },\n",
          -0.15 + 0.01 * i, 0.85 + 0.01 * j, -0.142 + 0.01 * i, 0.85 + 0.01 * j, -0.15 + 0.01 * i, 0.858 + 0.01 * j
    # Slivers in the planes x = 0 and z = 0 through light 1: edge-on, their boxes flat.
    for (i = 0; i < 6; i++) {
      y = 0.3 + 0.15 * i; z = -1.2 + 0.4 * i
      printf "    { \"type\": \"triangle\", \"vertices\": [[0, %.6f, %.6f], [0, %.6f, %.6f], [0, %.6f, %.6f]], \"material\": \"m\" },\n",
        y, z, y + 0.05, z + 0.3, y + 0.4, z + 0.01
      printf "    { \"type\": \"triangle\", \"vertices\": [[%.6f, %.6f, 0], [%.6f, %.6f, 0], [%.6f, %.6f, 0]], \"material\": \"m\" },\n",
        z, y, z + 0.3, y + 0.05, z + 0.01, y + 0.4
    }
    # Spheres on light 1'"'"'s cube diagonals and face edges (|x| = |y| or |y| = |z| from it).
    for (i = 0; i < 8; i++) {
      sx = (i % 2) ? 1 : -1; sz = (int(i / 2) % 2) ? 1 : -1; r = 0.7 + 0.1 * (i % 3)
      printf "    { \"type\": \"sphere\", \"center\": [%.6f, %.6f, %.6f], \"radius\": 0.08, \"material\": \"m\" },\n",
        sx * r, 1.5 - r, sz * r * (i < 4 ? 1 : 0)
    }
    # A crowd of small occluders around light 2.
    for (i = 0; i < 60; i++) {
      x = 1.25 + (rand() - 0.5) * 1.4; y = 0.75 + (rand() - 0.5) * 1.2; z = -0.5 + (rand() - 0.5) * 1.4
      if ((x - 1.25) ^ 2 + (y - 0.75) ^ 2 + (z + 0.5) ^ 2 < 0.04) continue
      if (i % 3) printf "    { \"type\": \"sphere\", \"center\": [%.6f, %.6f, %.6f], \"radius\": %.4f, \"material\": \"m\" },\n", x, y, z, 0.02 + 0.03 * rand()
      else printf "    { \"type\": \"triangle\", \"vertices\": [[%.6f, %.6f, %.6f], [%.6f, %.6f, %.6f], [%.6f, %.6f, %.6f]], \"material\": \"m\" },\n",
        x, y, z, x + 0.08, y, z + 0.01, x, y + 0.06, z + 0.05
    }
    # For the eye buffer: a triangle from behind the eye to in front of it (its box reaches
    # the eye'"'"'s plane: every tile), a sphere past the image'"'"'s left edge that pokes into
    # it, and a row of tiny spheres, each under a pixel, along a horizontal tile edge.
    print "    { \"type\": \"triangle\", \"vertices\": [[2.5, 2.5, 7], [2.8, 2.4, 7.2], [2.4, 1.2, 2]], \"material\": \"m\" },"
    print "    { \"type\": \"sphere\", \"center\": [-5.2, 1.2, 0], \"radius\": 0.9, \"material\": \"m\" },"
    # A sphere wholly behind the eye: in no tile.
    print "    { \"type\": \"sphere\", \"center\": [0.5, 2.5, 8], \"radius\": 0.5, \"material\": \"m\" },"
    for (i = 0; i < 40; i++)
      printf "    { \"type\": \"sphere\", \"center\": [%.6f, 1.62, 1.5], \"radius\": %.5f, \"material\": \"m\" },\n", -2 + 0.1 * i, 0.004 + 0.002 * (i % 5)
    print "    { \"type\": \"sphere\", \"center\": [-1.5, 0.4, 0.8], \"radius\": 0.4, \"material\": \"m\" } ] }"
  }'
}

# same RUNS NAME SCENE [render args]: on and off agree in each run of RUNS ("gpu f32,cpu f64").
same() {
  local runs=$1 name=$2 scene=$3
  shift 3
  local list run
  IFS=, read -ra list <<<"$runs"
  for run in "${list[@]}"; do
    set -- $run "$@"
    local backend=$1 p=$2
    shift 2
    local why=ok
    for lb in on off; do
      "$bin" render "$scene" -o "$work/$lb.exr" --aov "$work/$lb.aov.exr" --backend $backend --precision $p \
        --light-buffers $lb --eye-buffer $lb --stats-json "$work/$lb.json" --quiet "$@" 2>"$work/err" ||
        because "--light-buffers $lb --eye-buffer $lb: exit status $?: $(head -c 300 "$work/err")"
    done
    if [[ $why == ok ]]; then
      local c=$work/cmp.json
      "$bin" compare "$work/on.aov.exr" "$work/off.aov.exr" --fail 0 --depth-tolerance 0 --normal-tolerance 0 \
        --json >"$c" || because "decisions differ: objects in $(json_num object_mismatch "$c") pixels, hits in \
$(json_num hit_mismatch "$c"), shadows in $(json_num shadow_mismatch "$c")"
      "$bin" compare "$work/on.exr" "$work/off.exr" --fail 0 --json >"$c" ||
        because "the images differ by up to $(json_num max_error "$c")"
      [[ $(json_num light_buffers "$work/off.json") == 0 ]] || because "--light-buffers off built buffers"
      [[ $(json_num eye_buffer_tile "$work/off.json") == 0 ]] || because "--eye-buffer off built one"
      lights=$(json_num light_buffers "$work/on.json")
    fi
    check "$name, $backend $p: light and eye buffers on = off" "$why"
  done
}

for scene in "$scenes"/*.json; do
  name=$(basename "$scene" .json)
  # The GPU alone here: the reference's twin of the lookup is checked on the stress scenes
  # below, and against the GPU by the GPU-vs-CPU gates.
  same "gpu f32" "$name" "$scene" --width 64 --height 48 --spp 1
done

for seed in 1 2; do
  stress $seed >"$work/stress$seed.json"
  same "gpu f32,cpu f64" "stress $seed" "$work/stress$seed.json"
  why=ok
  [[ $lights == 2 ]] || because "$lights light buffers, expected 2 (the directional light has none)"
  for kind in empty list subtree; do
    n=$(json_num light_buffer_${kind}_cells "$work/on.json")
    [[ $n -gt 0 ]] || because "no $kind cells"
  done
  # 96 x 72 pixels: 12 x 9 tiles of 8 pixels. The triangle through the eye's plane is in
  # every tile, so none is empty.
  [[ $(json_num eye_buffer_tile "$work/on.json") == 8 && $(json_num eye_buffer_cells "$work/on.json") == 108 ]] ||
    because "eye buffer of $(json_num eye_buffer_cells "$work/on.json") tiles of $(json_num eye_buffer_tile "$work/on.json") pixels, expected 108 of 8"
  [[ $(json_num eye_buffer_empty_cells "$work/on.json") == 0 && $(json_num eye_buffer_subtree_cells "$work/on.json") -gt 0 ]] ||
    because "eye buffer tiles: $(json_num eye_buffer_empty_cells "$work/on.json") empty (expected 0), $(json_num eye_buffer_subtree_cells "$work/on.json") with a subtree"
  check "stress $seed: two light buffers with cells of every kind, and the eye buffer" "$why"
  # The same scene seen by a parallel camera, at 4 samples a pixel: the eye buffer's other
  # projection, and samples spread over each pixel.
  sed 's/"camera": {/"camera": { "projection": "parallel", "view_height": 5,/; s/, "fov_y_deg": 50//' "$work/stress$seed.json" >"$work/parallel$seed.json"
  same "gpu f32,cpu f64" "stress $seed, parallel" "$work/parallel$seed.json" --spp 4
  why=ok
  [[ $(json_num eye_buffer_empty_cells "$work/on.json") -gt 0 && $(json_num eye_buffer_list_cells "$work/on.json") -gt 0 ]] ||
    because "parallel eye buffer: $(json_num eye_buffer_empty_cells "$work/on.json") empty tiles, $(json_num eye_buffer_list_cells "$work/on.json") with a list"
  check "stress $seed, parallel: the eye buffer has empty tiles and lists" "$why"
done
finish
