#!/usr/bin/env bash
# Writes a scene of N named things, for the linear-parsing test and tools/bench_parse.sh.
# Usage: gen_scale.sh KIND N OUT
#   json-materials  N materials and N spheres, sphere i using material i
#   json-dup        N materials, the last one a repeat of the first
#   json-unknown    N materials and one sphere naming a material that does not exist
#   test-materials  a .test file of N spheres, each with its own diffuse colour
#   test-shared     a .test file of N spheres alternating between two colours
#   test-vertices   a .test file of N vertices and N/3 triangles
#   objects-TYPE    N objects of TYPE (sphere, triangle, plane, ellipsoid, cylinder, cone,
#                   paraboloid, hyperboloid, box, quadric, csg, csg-mesh, mesh), one material;
#                   the mesh kinds name OUT's folder's cube.obj (written here)
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
objects-*)
  type=${kind#objects-}
  [[ $type == mesh || $type == csg-mesh ]] &&
    printf 'v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nf 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 7 3\nf 4 8 7\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n' \
      >"$(dirname "$out")/cube.obj"
  awk -v n="$n" -v type="$type" -v head="$json_head" 'BEGIN {
    print head; print "  \"materials\": { \"m\": { \"diffuse\": [0.5, 0.5, 0.5] } },"; print "  \"objects\": ["
    for (i = 0; i < n; i++) {
      x = i % 400 - 200; y = int(i / 400) % 400 - 200; c = sprintf("[%d, %d, 0]", x, y)
      if (type == "sphere") o = sprintf("\"center\": %s, \"radius\": 0.4", c)
      else if (type == "triangle") o = sprintf("\"vertices\": [[%d, %d, 0], [%g, %d, 0], [%d, %g, 0]]", x, y, x + 0.5, y, x, y + 0.5)
      else if (type == "plane") o = sprintf("\"point\": [0, 0, %d], \"normal\": [0, 0, 1]", -i)
      else if (type == "ellipsoid") o = sprintf("\"center\": %s, \"radii\": [0.4, 0.3, 0.2]", c)
      else if (type == "cylinder") o = sprintf("\"center\": %s, \"axis\": [0, 1, 0], \"radius\": 0.3, \"height\": 0.6", c)
      else if (type == "cone") o = sprintf("\"apex\": %s, \"axis\": [0, -1, 0], \"angle_deg\": 20, \"height\": 0.6", c)
      else if (type == "paraboloid") o = sprintf("\"vertex\": %s, \"axis\": [0, 1, 0], \"radius\": 0.3, \"height\": 0.6", c)
      else if (type == "hyperboloid") o = sprintf("\"center\": %s, \"axis\": [0, 1, 0], \"radius\": 0.2, \"end_radius\": 0.3, \"height\": 0.6", c)
      else if (type == "box") o = sprintf("\"min\": [%d, %d, 0], \"max\": [%g, %g, 0.5]", x, y, x + 0.5, y + 0.5)
      else if (type == "quadric") o = sprintf("\"matrix\": [[1, 0, 0, %d], [0, 1, 0, %d], [0, 0, 1, 0], [%d, %d, 0, %d]], \"bounds\": { \"min\": [%d, %d, -1], \"max\": [%d, %d, 1] }", -x, -y, -x, -y, x * x + y * y - 0.16, x - 1, y - 1, x + 1, y + 1)
      else if (type == "csg") o = sprintf("\"op\": \"difference\", \"left\": { \"type\": \"sphere\", \"center\": %s, \"radius\": 0.4 }, \"right\": { \"type\": \"box\", \"min\": [%d, %d, 0], \"max\": [%g, %g, 0.5] }", c, x, y, x + 0.5, y + 0.5)
      else if (type == "csg-mesh") o = sprintf("\"op\": \"difference\", \"left\": { \"type\": \"mesh\", \"file\": \"cube.obj\", \"transform\": { \"scale\": [0.4, 0.4, 0.4], \"translate\": %s } }, \"right\": { \"type\": \"sphere\", \"center\": %s, \"radius\": 0.3 }", c, c)
      else if (type == "mesh") o = sprintf("\"file\": \"cube.obj\", \"transform\": { \"scale\": [0.4, 0.4, 0.4], \"translate\": %s }", c)
      t = type == "csg-mesh" ? "csg" : type
      printf "    { \"type\": \"%s\", %s, \"material\": \"m\" }%s\n", t, o, i < n - 1 ? "," : ""
    }
    print "  ]"; print "}" }' >"$out" ;;
*) echo "gen_scale.sh: unknown kind $kind" >&2; exit 2 ;;
esac
