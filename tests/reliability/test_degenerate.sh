#!/usr/bin/env bash
# Degenerate geometry the CPU renders, the GPU renders (issue 13, class 5). Generated piles
# of exactly coincident objects (N copies of a triangle, of a sphere, of a transformed
# sphere and of an ellipsoid, in several materials, in front of a distinct sphere): on the
# GPU in f32 and f64 each must render, validation-clean, what the CPU reference renders in
# the same precision, with the repeats left out of the BVH, and leaving them out must not
# change a bit (the CPU's BVH against its brute force).
# A ray through a pile of N near-coincident (not identical) triangles can exceed the GPU's
# loop budget on llvmpipe: then the refusal names the scene file, the line and field of an
# object of the pile, and the pixel, and offers the CPU backend.
# Usage: test_degenerate.sh VKRAYCAST WORKDIR
set -uo pipefail
bin=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
pile() { # N kind -> scene
  awk -v n="$1" -v kind="$2" 'BEGIN {
    print "{ \"image\": { \"width\": 48, \"height\": 36 }, \"camera\": { \"eye\": [0.3, 0.4, 5], \"look_at\": [0, 0, 0] },"
    print "  \"materials\": { \"a\": { \"diffuse\": [0.8, 0.2, 0.2], \"specular\": [0.3, 0.3, 0.3], \"shininess\": 20 },"
    print "                 \"b\": { \"diffuse\": [0.2, 0.8, 0.2] }, \"c\": { \"diffuse\": [0.2, 0.2, 0.8], \"mirror\": 0.3 } },"
    print "  \"lights\": [ { \"type\": \"point\", \"position\": [2, 3, 4], \"intensity\": [20, 20, 20] } ],"
    print "  \"objects\": [ { \"type\": \"sphere\", \"center\": [0.5, 0.2, -2], \"radius\": 1, \"material\": \"b\" }"
    split("a b c", m, " ")
    for (i = 0; i < n; i++) {
      mat = m[i % 3 + 1]
      if (kind == "triangle") o = "{ \"type\": \"triangle\", \"vertices\": [[-1, -1, 0], [1, -1, 0], [0, 1, 0.5]]"
      else if (kind == "near-triangle") o = sprintf("{ \"type\": \"triangle\", \"vertices\": [[-1, -1, %.9f], [1, -1, 0], [0, 1, 0.5]]", i * 1e-7)
      else if (kind == "sphere") o = "{ \"type\": \"sphere\", \"center\": [0, 0, 0.5], \"radius\": 0.6"
      else if (kind == "scaled-sphere") o = "{ \"type\": \"sphere\", \"center\": [0, 0, 0.5], \"radius\": 0.6, \"transform\": { \"scale\": [1.5, 0.7, 1] }"
      else o = "{ \"type\": \"ellipsoid\", \"center\": [0, 0, 0.5], \"radii\": [0.9, 0.5, 0.6]"
      printf ",\n    %s, \"material\": \"%s\" }", o, mat
    }
    print "\n  ] }" }'
}
stat() { sed -n "s/.*\"$1\":[[:space:]]*\([0-9]*\).*/\1/p" "$2"; }
# Under the sanitizers (tools/test.sh's second pass) f32 alone: the host code that leaves
# the repeats out is the same in both precisions; their numbers are the first pass's.
precisions=(f32 f64)
[[ -z ${ASAN_OPTIONS:-} ]] || precisions=(f32)
for kind in triangle sphere scaled-sphere ellipsoid; do
  n=10000
  [[ $kind == triangle ]] || n=2000
  pile $n $kind >"$work/$kind.json"
  for p in "${precisions[@]}"; do
    why=ok
    for backend in gpu cpu; do
      "$bin" render "$work/$kind.json" -o "$work/$kind.$backend.exr" --aov "$work/$kind.$backend.aov.exr" \
        --backend $backend --precision $p --quiet --stats-json "$work/$kind.$backend.json" 2>"$work/err" ||
        why="$backend exit status $?: $(head -c 300 "$work/err")"
    done
    # Leaving the repeats out changes nothing: the CPU without a BVH tests every copy.
    "$bin" render "$work/$kind.json" -o "$work/$kind.none.exr" --aov "$work/$kind.none.aov.exr" --backend cpu \
      --precision $p --accel none --quiet 2>"$work/err" || why="cpu --accel none exit status $?"
    if [[ $why == ok ]]; then
      "$bin" compare "$work/$kind.cpu.aov.exr" "$work/$kind.none.aov.exr" --fail 0 --depth-tolerance 0 \
        --normal-tolerance 0 >/dev/null ||
        why="the CPU's BVH and brute force differ"
      # The GPU against the CPU as everywhere (tools/gpu_vs_cpu.sh): colours within 1e-4,
      # at most 1 pixel in 500 with another decision (an edge decided the other way).
      "$bin" compare "$work/$kind.gpu.exr" "$work/$kind.cpu.exr" --fail 1e-4 >/dev/null || why="$why; images differ"
      "$bin" compare "$work/$kind.gpu.aov.exr" "$work/$kind.cpu.aov.exr" --fail 1e30 --decisions 3 >/dev/null ||
        why="$why; decisions differ"
      left=$(stat bvh_repeats_left_out "$work/$kind.gpu.json")
      [[ $left == $((n - 1)) ]] || why="$why; $left repeats left out of the BVH, expected $((n - 1))"
    fi
    check "$n coincident ${kind}s, $p: GPU = CPU" "$why"
  done
done
pile 10000 near-triangle >"$work/near.json"
"$bin" render "$work/near.json" -o "$work/near.png" --quiet 2>"$work/err"
got=$?
if [[ $got == 0 ]]; then
  check "10000 near-coincident triangles on the GPU" ok # a device with a larger loop budget
else
  why=ok
  [[ $got == 2 ]] || why="exit status $got, expected 0 or 2"
  # The scene file, the line and index of one of the pile (objects 1..10000), the pixel.
  grep -qE "near.json:[0-9]+:5: error: objects\[[0-9]+\]: a ray through pixel \([0-9]+, [0-9]+\) was testing" "$work/err" &&
    grep -q -- "--backend cpu renders it" "$work/err" && ! grep -q "tile" "$work/err" ||
    why="$why; stderr: $(head -c 400 "$work/err")"
  [[ ! -e $work/near.png ]] || why="$why; an image was written"
  check "10000 near-coincident triangles on the GPU: refused naming the scene and an object" "$why"
fi
"$bin" render "$work/near.json" -o "$work/near.png" --quiet --backend cpu
check "10000 near-coincident triangles on the CPU" "$([[ $? == 0 ]] && echo ok || echo failed)"
finish
