#!/usr/bin/env bash
# Writes a scene of N named things, for the linear-parsing test and tools/bench_parse.sh.
# Usage: gen_scale.sh KIND N OUT
#   json-materials  N materials and N spheres, sphere i using material i
#   json-dup        N materials, the last one a repeat of the first
#   json-unknown    N materials and one sphere naming a material that does not exist
#   test-materials  a .test file of N spheres, each with its own diffuse colour
#   test-shared     a .test file of N spheres alternating between two colours
#   test-vertices   a .test file of N vertices and N/3 triangles
set -euo pipefail
kind=$1 n=$2 out=$3
json_head='{ "image": { "width": 8, "height": 8 }, "camera": { "eye": [0, 0, 50], "look_at": [0, 0, 0] },'
case $kind in
json-*)
  awk -v n="$n" -v kind="$kind" -v head="$json_head" 'BEGIN {
    print head; print "  \"materials\": {"
    for (i = 0; i < n; i++) {
      name = (kind == "json-dup" && i == n - 1) ? "m0" : "m" i
      printf "    \"%s\": { \"diffuse\": [0.5, 0.5, %.6f] }%s\n", name, i / n, i < n - 1 ? "," : ""
    }
    print "  },"; print "  \"objects\": ["
    if (kind == "json-unknown") print "    { \"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m" n "\" }"
    else for (i = 0; i < n; i++)
      printf "    { \"type\": \"sphere\", \"center\": [%d, %d, 0], \"radius\": 0.4, \"material\": \"m%d\" }%s\n",
             i % 400 - 200, int(i / 400) % 400 - 200, i, i < n - 1 ? "," : ""
    print "  ]"; print "}" }' >"$out" ;;
test-*)
  awk -v n="$n" -v kind="$kind" 'BEGIN {
    print "size 8 8"; print "camera 0 0 50 0 0 0 0 1 0 45"
    if (kind == "test-vertices") {
      for (i = 0; i < n; i++) printf "vertex %d %d %d\n", i % 3 == 1, i % 3 == 2, int(i / 3)
      for (i = 0; i + 2 < n; i += 3) printf "tri %d %d %d\n", i, i + 1, i + 2
    } else for (i = 0; i < n; i++) {
      printf "diffuse 0.5 0.5 %.7f\n", kind == "test-shared" ? i % 2 : i / n
      printf "sphere %d %d 0 0.4\n", i % 400 - 200, int(i / 400) % 400 - 200
    } }' >"$out" ;;
*) echo "gen_scale.sh: unknown kind $kind" >&2; exit 2 ;;
esac
