#!/usr/bin/env bash
# Parsing is linear (issue 13, class 4). Generated scenes of 200,000 named things (JSON
# materials referenced by as many spheres, .test material states and vertices) must load
# and resolve every reference; a repeated or unknown name at the far end of such a file is
# reported with its own line. Every kind of object at scale too: 200,000 of each
# primitive and quadric kind, 100,000 composites, and 8,000 meshes and mesh composites
# naming one file (each mesh located its line from the file's start and imported its
# file again: 8,000 took 34 s). No clock is read: a quadratic parser (minutes at this size)
# fails through the test's ctest timeout; tools/bench_parse.sh measures the scaling.
# Usage: test_parse_scale.sh VKRAYCAST WORKDIR
set -uo pipefail
bin=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
gen="$(dirname "$0")/gen_scale.sh"
n=200000
stat() { sed -n "s/.*\"$1\":[[:space:]]*\([0-9]*\).*/\1/p" "$work/stats.json"; }
expect_counts() { # name scene materials spheres triangles
  local why=ok
  "$bin" render "$2" -o "$work/o.png" --backend cpu --quiet --stats-json "$work/stats.json" 2>"$work/err" ||
    why="exit status $?: $(head -c 300 "$work/err")"
  if [[ $why == ok ]]; then
    local got="$(stat materials) $(stat spheres) $(stat triangles)"
    [[ $got == "$3 $4 $5" ]] || why="materials spheres triangles: $got, expected $3 $4 $5"
  fi
  check "$1" "$why"
}
"$gen" json-materials $n "$work/materials.json"
expect_counts "$n JSON materials, each used once" "$work/materials.json" $n $n 0
"$gen" json-dup $n "$work/dup.json"
expect_refusal "a repeated material at line $((n + 2))" "$work/dup.json" "dup.json:$((n + 2)):11: error: materials.m0: material defined twice" --backend cpu
"$gen" json-unknown $n "$work/unknown.json"
# The nearest of the n names is suggested (m0..m199999: "m20000" is one edit from "m200000").
expect_refusal "an unknown material after $n" "$work/unknown.json" "unknown.json:$((n + 5)):71: error: objects[0].material: unknown material; did you mean \"m$((n / 10))\"? (\"m$n\")" --backend cpu
# objects-TYPE N: the statistics field that counts them, and how many per object.
for spec in "sphere $n spheres 1" "triangle $n triangles 1" "plane $n planes 1" "ellipsoid $n quadrics 1" \
  "cylinder $n quadrics 1" "cone $n quadrics 1" "paraboloid $n quadrics 1" "hyperboloid $n quadrics 1" \
  "box $n quadrics 1" "quadric $n quadrics 1" "csg $((n / 2)) composites 1" "mesh 8000 triangles 12" \
  "csg-mesh 8000 composites 1"; do
  read -r type count field per <<<"$spec"
  "$gen" "objects-$type" "$count" "$work/objects.json"
  why=ok
  "$bin" render "$work/objects.json" -o "$work/o.png" --backend cpu --quiet --stats-json "$work/stats.json" \
    2>"$work/err" || why="exit status $?: $(head -c 300 "$work/err")"
  [[ $why != ok || $(stat "$field") == $((count * per)) ]] || why="$field: $(stat "$field"), expected $((count * per))"
  check "$count objects of type $type" "$why"
done
"$gen" test-materials $n "$work/materials.test"
expect_counts "$n .test material states" "$work/materials.test" $n $n 0
"$gen" test-shared $n "$work/shared.test"
expect_counts "$n .test spheres sharing 2 materials" "$work/shared.test" 2 $n 0
"$gen" test-vertices $n "$work/vertices.test"
expect_counts "$n .test vertices" "$work/vertices.test" 1 0 $((n / 3))
finish
