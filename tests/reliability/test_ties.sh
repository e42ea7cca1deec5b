#!/usr/bin/env bash
# Ties between coplanar neighbours: the BVH must pick what brute force picks, bit for bit
# (docs/numerics.md §4, "Ties and the BVH"). Fans of N triangles around one vertex put
# every pixel on a spoke close to two or more triangles at one distance; there the tie
# rule (the lower object number) decides, and it can only if the traversal tests every
# triangle that ties. The box cull's margin (RC_BOX_NEAR_SCALE) is what ensures that:
# culling at exactly the nearest hit dropped tying triangles in 5 to 12 pixels of these
# fans seen head-on, in f32 and in f64. Fans flat and tilted 30 degrees, seen head-on and
# obliquely, on the GPU and the CPU, in f32 and f64.
# Usage: test_ties.sh VKRAYCAST WORKDIR
set -uo pipefail
bin=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"

# fan N TILT_DEGREES CX CY parallel|perspective -> scene: N triangles around (CX, CY, 0),
# their plane turned TILT_DEGREES about the x axis, alternating two materials.
fan() {
  awk -v n="$1" -v tilt="$2" -v cx="$3" -v cy="$4" -v proj="$5" 'BEGIN {
    pi = 3.14159265358979323846; ct = cos(tilt * pi / 180); st = sin(tilt * pi / 180)
    print "{ \"version\": 1, \"image\": { \"width\": 128, \"height\": 128 },"
    if (proj == "parallel")
      printf "  \"camera\": { \"projection\": \"parallel\", \"eye\": [%.17g, %.17g, %.17g], \"look_at\": [%.17g, %.17g, %.17g], \"view_height\": 1.2 },\n",
        cx, cy * ct - 5 * st, cy * st + 5 * ct, cx, cy * ct, cy * st
    else
      printf "  \"camera\": { \"eye\": [%.17g, %.17g, %.17g], \"look_at\": [%.17g, %.17g, %.17g], \"fov_y_deg\": 30 },\n",
        cx + 0.7, cy * ct - 3 * st - 0.4, cy * st + 3 * ct, cx, cy * ct, cy * st
    print "  \"background\": [1, 0, 0],"
    print "  \"materials\": { \"a\": { \"diffuse\": [0.8, 0.8, 0.8] }, \"b\": { \"diffuse\": [0.1, 0.1, 0.8] } },"
    print "  \"lights\": [ { \"type\": \"directional\", \"direction\": [0.1, 0.2, -1], \"intensity\": [1, 1, 1] } ],"
    print "  \"objects\": ["
    for (i = 0; i < n; i++) {
      a = 2 * pi * i / n; b = 2 * pi * ((i + 1) % n) / n
      y1 = cy + sin(a); y2 = cy + sin(b)
      printf "%s    { \"type\": \"triangle\", \"vertices\": [[%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g]], \"material\": \"%s\" }",
        (i ? ",\n" : ""), cx, cy * ct, cy * st, cx + cos(a), y1 * ct, y1 * st, cx + cos(b), y2 * ct, y2 * st, (i % 2 ? "b" : "a")
    }
    print "\n  ] }" }'
}

for n in 16 1000; do
  for view in "0 0 0 parallel" "0 0 0 perspective" "30 0.3 0.2 parallel" "30 0.3 0.2 perspective"; do
    # The 1000-triangle fan head-on only (tests/extremes S09 has it too): the oblique and
    # tilted views of it never differed, and they cost the suite 25 s.
    [[ $n == 16 || $view == "0 0 0 parallel" ]] || continue
    set -- $view
    name="fan_${n}_tilt$1_$4"
    fan "$n" "$@" >"$work/$name.json"
    for backend in gpu cpu; do
      for p in f32 f64; do
        why=ok
        for accel in bvh none; do
          "$bin" render "$work/$name.json" -o "$work/$accel.exr" --aov "$work/$accel.aov.exr" --backend $backend \
            --precision $p --accel $accel --quiet 2>"$work/err" || because "$accel: exit status $?: $(head -c 300 "$work/err")"
        done
        if [[ $why == ok ]]; then
          c=$work/cmp.json
          "$bin" compare "$work/bvh.aov.exr" "$work/none.aov.exr" --fail 0 --depth-tolerance 0 --normal-tolerance 0 \
            --json >"$c" ||
            because "the BVH and brute force differ: objects in $(json_num object_mismatch "$c") pixels, hits in \
$(json_num hit_mismatch "$c"), shadows in $(json_num shadow_mismatch "$c"), colour by up to $(json_num max_error "$c")"
        fi
        check "$name, $backend $p: BVH = brute force" "$why"
      done
    done
  done
done
finish
