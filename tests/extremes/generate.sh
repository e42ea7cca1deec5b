#!/usr/bin/env bash
# Writes the extreme-case scenes of docs/extremes.md (S01-S21, S23) into tests/extremes/scenes/.
# The files are committed; this script is how they were made (rerun it after a change).
#   tests/extremes/generate.sh [OUTDIR]
set -euo pipefail
out=${1:-$(dirname "$0")/scenes}
mkdir -p "$out"
rm -f "$out"/*.json "$out"/*.obj

MATERIALS='"materials": {
    "white": { "ambient": [0.05, 0.05, 0.05], "diffuse": [0.8, 0.8, 0.8], "specular": [0.3, 0.3, 0.3], "shininess": 20 },
    "red":   { "ambient": [0.05, 0.0, 0.0], "diffuse": [0.8, 0.1, 0.1] },
    "blue":  { "ambient": [0.0, 0.0, 0.05], "diffuse": [0.1, 0.1, 0.8] },
    "green": { "ambient": [0.0, 0.05, 0.0], "diffuse": [0.1, 0.8, 0.1] } }'

# scene NAME SIZE CAMERA LIGHTS OBJECTS [BACKGROUND]
scene() {
  cat >"$out/$1.json" <<JSON
{
  "version": 1,
  "image": { "width": ${2%x*}, "height": ${2#*x} },
  "camera": { $3 },
  "background": ${6:-[0, 0, 0]},
  "ambient_light": [1, 1, 1],
  $MATERIALS,
  "lights": [ $4 ],
  "objects": [
    $5
  ]
}
JSON
}
g() { awk "BEGIN { printf \"%.17g\", $1 }"; }  # evaluate a number
v3() { echo "[$(g "$1"), $(g "$2"), $(g "$3")]"; }
tri() { echo "{ \"type\": \"triangle\", \"vertices\": [$1, $2, $3], \"material\": \"${4:-white}\" }"; }
sph() { echo "{ \"type\": \"sphere\", \"center\": $1, \"radius\": $(g "$2"), \"material\": \"${3:-white}\" }"; }
point() { echo "{ \"type\": \"point\", \"position\": $1, \"intensity\": [$(g "$2"), $(g "$2"), $(g "$2")] }"; }
sun() { echo "{ \"type\": \"directional\", \"direction\": $1, \"intensity\": [1, 1, 1] }"; }
# A unit cube as 12 triangles, centred at (x, y, z) with half-size h.
cube() {
  local x=$1 y=$2 z=$3 h=$4 m=${5:-white}
  local -a c
  for i in 0 1 2 3 4 5 6 7; do
    c[i]=$(v3 "$x + (($i % 2) * 2 - 1) * $h" "$y + ((int($i / 2) % 2) * 2 - 1) * $h" "$z + ((int($i / 4)) * 2 - 1) * $h")
  done
  local faces="0 1 3 0 3 2 4 6 7 4 7 5 0 4 5 0 5 1 2 3 7 2 7 6 0 2 6 0 6 4 1 5 7 1 7 3" s="" sep=""
  set -- $faces
  while [ $# -gt 0 ]; do s+="$sep$(tri "${c[$1]}" "${c[$2]}" "${c[$3]}" "$m")"; sep=", "; shift 3; done
  echo "$s"
}
# A closed UV sphere mesh of radius 2 with shared vertices (OBJ): ROWS x COLS quads.
uv_sphere_obj() {
  awk -v rows=32 -v cols=64 'BEGIN {
    pi = 3.14159265358979323846
    print "# closed UV sphere, radius 2: tests/extremes/generate.sh"
    print "v 0 2 0"
    for (i = 1; i < rows; i++) for (j = 0; j < cols; j++) {
      th = pi * i / rows; ph = 2 * pi * j / cols
      printf "v %.9g %.9g %.9g\n", 2 * sin(th) * cos(ph), 2 * cos(th), 2 * sin(th) * sin(ph)
    }
    print "v 0 -2 0"
    south = 2 + (rows - 1) * cols
    for (j = 0; j < cols; j++) printf "f 1 %d %d\n", 2 + (j + 1) % cols, 2 + j
    for (i = 1; i < rows - 1; i++) for (j = 0; j < cols; j++) {
      a = 2 + (i - 1) * cols + j; b = 2 + (i - 1) * cols + (j + 1) % cols
      c = 2 + i * cols + j; d = 2 + i * cols + (j + 1) % cols
      printf "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c
    }
    for (j = 0; j < cols; j++) printf "f %d %d %d\n", south, 2 + (rows - 2) * cols + j, 2 + (rows - 2) * cols + (j + 1) % cols
  }' >"$out/uv_sphere.obj"
}
# An N x N grid of quads (2N^2 triangles) on [-1, 1]^2 in the z = 0 plane (OBJ).
grid_obj() {
  awk -v n="$1" 'BEGIN {
    print "# tessellated square: tests/extremes/generate.sh"
    for (i = 0; i <= n; i++) for (j = 0; j <= n; j++) printf "v %.9g %.9g 0\n", -1 + 2 * j / n, -1 + 2 * i / n
    for (i = 0; i < n; i++) for (j = 0; j < n; j++) {
      a = 1 + i * (n + 1) + j; b = a + 1; c = a + n + 1; d = c + 1
      printf "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c
    }
  }' >"$out/$2"
}
mesh() { echo "{ \"type\": \"mesh\", \"file\": \"$1\", \"material\": \"${3:-white}\", \"transform\": { $2 } }"; }
persp() { echo "\"eye\": $1, \"look_at\": $2, \"up\": ${4:-[0, 1, 0]}, \"fov_y_deg\": $(g "$3")"; }
ortho() { echo "\"projection\": \"parallel\", \"eye\": $1, \"look_at\": $2, \"up\": ${4:-[0, 1, 0]}, \"view_height\": $(g "$3")"; }

uv_sphere_obj
grid_obj 64 grid64.obj

# S01 baseline and S02 its parallel twin; S13 moves both by T (scene and camera).
s01_objects() {
  local x=$1 y=$2 z=$3
  echo "$(sph "$(v3 "$x" "$y + 1" "$z - 5")" 1), $(cube "$x + 1.8" "$y + 0.5" "$z - 3.5" 0.5 red),
    $(tri "$(v3 "$x - 6" "$y" "$z + 2")" "$(v3 "$x + 6" "$y" "$z + 2")" "$(v3 "$x + 6" "$y" "$z - 12")"),
    $(tri "$(v3 "$x - 6" "$y" "$z + 2")" "$(v3 "$x + 6" "$y" "$z - 12")" "$(v3 "$x - 6" "$y" "$z - 12")")"
}
s01_light() { point "$(v3 "$1 - 3" "$2 + 6" "$3 + 1")" 60; }
scene S01_baseline 160x120 "$(persp "[0, 2, 2]" "[0, 0.8, -5]" 45)" "$(s01_light 0 0 0)" "$(s01_objects 0 0 0)"
scene S02_parallel 160x120 "$(ortho "[0, 2, 2]" "[0, 0.8, -5]" 5)" "$(s01_light 0 0 0)" "$(s01_objects 0 0 0)"
for t in 1e3 1e5 1e7; do
  scene "S13_translate_x_$t" 160x120 "$(persp "$(v3 "$t" 2 2)" "$(v3 "$t" 0.8 -5)" 45)" "$(s01_light "$t" 0 0)" \
    "$(s01_objects "$t" 0 0)"
  scene "S13_translate_xyz_$t" 160x120 "$(persp "$(v3 "$t" "$t + 2" "$t + 2")" "$(v3 "$t" "$t + 0.8" "$t - 5")" 45)" \
    "$(s01_light "$t" "$t" "$t")" "$(s01_objects "$t" "$t" "$t")"
done

# S03 sphere distance sweep (r = 1) and S04 the same ratios at other scales: the field of
# view makes the sphere span 60 % of the image height.
fov_for() { g "2 * atan2(($1 / $2) / sqrt(1 - ($1 / $2) ^ 2) / 0.6, 1) * 180 / 3.14159265358979323846"; }
sweep() {
  local name=$1 r=$2 d=$3
  scene "$name" 96x96 "$(persp "[0, 0, 0]" "$(v3 0 0 "-$d")" "$(fov_for "$r" "$d")")" "$(sun "[0.4, -0.5, -1]")" \
    "$(sph "$(v3 0 0 "-$d")" "$r")"
}
for d in 1e1 1e2 1e3 1e4 1e5 1e6 1e8; do sweep "S03_distance_$d" 1 "$d"; done
for d in 1e-5 1e-3 1e0; do sweep "S04_r1e-6_D$d" 1e-6 "$d"; done
for d in 1e7 1e9; do sweep "S04_r1e6_D$d" 1e6 "$d"; done
sweep S04_r1e-20_D1e-19 1e-20 1e-19

# S05 huge sphere (R = 1e6) as ground, camera at height h looking 5 degrees down, a unit
# sphere resting on it 20 units ahead.
for h in 1e3 1e1 1e0 1e-1; do
  dz=$(g "20"); drop=$(g "$h + 1 - 1")
  scene "S05_ground_h$h" 128x96 "$(persp "$(v3 0 "$h" 0)" "$(v3 0 "$h - 20 * 0.0874886635" -20)" 40)" \
    "$(sun "[0.3, -1, -0.4]")" "$(sph "[0, -1000000, 0]" 1e6 blue), $(sph "$(v3 0 1 -20)" 1)"
done

# S06 grazing silhouettes: a parallel view whose window just covers the unit sphere (the
# edge pixels graze it), and a camera inside the sphere.
scene S06_grazing 128x128 "$(ortho "[0, 0, 10]" "[0, 0, 0]" 2.0000002)" "$(sun "[0, 0, -1]")" "$(sph "[0, 0, 0]" 1)"
scene S06_inside 96x96 "$(persp "[0.3, 0.2, 0.1]" "[0.3, 0.2, -1]" 150)" "$(point "[0, 0, 0]" 1)" "$(sph "[0, 0, 0]" 1)"

# S07 closed-mesh watertightness: the camera inside a closed UV sphere (4,032 triangles),
# at the origin, at Embree's test position and at 1e6. Every ray must hit. S10: scaled.
s07() {
  scene "$1" 192x192 "$(persp "$(v3 "$2 + 0.3" "$3 + 0.2" "$4 + 0.1")" "$(v3 "$2 + 0.3" "$3 + 0.2" "$4 - 1")" 150)" \
    "$(point "$(v3 "$2" "$3" "$4")" 1)" "$(mesh uv_sphere.obj "\"translate\": $(v3 "$2" "$3" "$4")")"
}
s07 S07_closed_mesh_origin 0 0 0
s07 S07_closed_mesh_embree 148376 1234 -223423
s07 S07_closed_mesh_1e6 1e6 1e6 1e6
for s in 1e-6 1e-3 1e3 1e6; do
  scene "S10_mesh_scale_$s" 192x192 "$(persp "$(v3 "0.3 * $s" "0.2 * $s" "0.1 * $s")" "$(v3 "0.3 * $s" "0.2 * $s" "-$s")" 150)" \
    "$(point "[0, 0, 0]" "$s * $s")" "$(mesh uv_sphere.obj "\"scale\": $(v3 "$s" "$s" "$s")")"
done

# S08 crack test: a 64 x 64-quad square over a red background, seen at 0, 60 and 85
# degrees from its normal (the window stays inside the square), and moved to 1e5.
for a in 0 60 85; do
  for t in 0 1e5; do
    c=$(g "cos($a * 3.14159265358979323846 / 180)"); s=$(g "sin($a * 3.14159265358979323846 / 180)")
    scene "S08_cracks_${a}deg_at_$t" 128x128 "$(ortho "$(v3 "$t" "$t - 5 * $s" "$t + 5 * $c")" "$(v3 "$t" "$t" "$t")" "1.8 * $c")" \
      "$(sun "$(v3 0 "$s" "-$c")")" "$(mesh grid64.obj "\"scale\": [5, 5, 5], \"translate\": $(v3 "$t" "$t" "$t")")" "[1, 0, 0]"
  done
done

# S09 slivers: closed triangle fans (discs of N needles around a centre) in front of a red
# background, and one triangle with a 1e-6 edge beside edges of length 1.
for n in 1000; do
  fan=$(awk -v n="$n" 'BEGIN { pi = 3.14159265358979323846
    for (i = 0; i < n; i++) { a = 2 * pi * i / n; b = 2 * pi * ((i + 1) % n) / n
      printf "%s{ \"type\": \"triangle\", \"vertices\": [[0, 0, 0], [%.17g, %.17g, 0], [%.17g, %.17g, 0]], \"material\": \"white\" }", (i ? ",\n    " : ""), cos(a), sin(a), cos(b), sin(b) } }')
  scene "S09_fan_$n" 128x128 "$(ortho "[0, 0, 5]" "[0, 0, 0]" 1.2)" "$(sun "[0, 0, -1]")" "$fan" "[1, 0, 0]"
done
# A unit square cut into three strips with a sliver of width w (aspect 1/w) in the middle;
# the parallel window, 4 w high, looks straight at the sliver and its two neighbours.
for w in 1e-3 1e-5 1e-7; do
  a="$(v3 "0.5" 0 0)"; b="$(v3 "0.5 + $w" 0 0)"; c="$(v3 "0.5 + $w" 1 0)"; d="$(v3 "0.5" 1 0)"
  scene "S09_sliver_$w" 64x64 "$(ortho "$(v3 "0.5 + $w / 2" 0.5 5)" "$(v3 "0.5 + $w / 2" 0.5 0)" "4 * $w")" "$(sun "[0, 0, -1]")" \
    "$(tri "[0, 0, 0]" "$a" "$d"), $(tri "[0, 0, 0]" "$d" "[0, 1, 0]"), $(tri "$a" "$b" "$c"), $(tri "$a" "$c" "$d"),
    $(tri "$b" "[1, 0, 0]" "[1, 1, 0]"), $(tri "$b" "[1, 1, 0]" "$c")" "[1, 0, 0]"
done
scene S09_needle 128x128 "$(ortho "[0, 0.5, 5]" "[0, 0.5, 0]" 1.2)" "$(sun "[0.2, 0, -1]")" \
  "$(tri "[0, 0, 0]" "[1e-6, 0, 0]" "[0.5, 1, 0]"), $(tri "[1e-6, 0, 0]" "[0.6, 0, 0]" "[0.5, 1, 0]"), $(tri "[-0.6, 0, 0]" "[0, 0, 0]" "[0.5, 1, 0]")" "[1, 0, 0]"

# S11 huge ground triangle (vertices at +-1e6 and +-1e7), camera 1 unit above it, a small
# box on it (its contact shadow must stay).
for e in 1e6 1e7; do
  scene "S11_huge_triangle_$e" 128x96 "$(persp "[0, 1, 0]" "[0, 0.3, -4]" 50)" "$(sun "[0.5, -1, -0.3]")" \
    "$(tri "$(v3 "-$e" 0 "$e")" "$(v3 "$e" 0 "$e")" "$(v3 0 0 "-$e")"), $(cube 0 0.25 -4 0.25 red)"
done

# S12 coincident surfaces: overlapping coplanar triangles (different colours), two
# identical spheres, a triangle in a sphere's tangent plane.
scene S12_coincident 128x96 "$(persp "[0, 1, 5]" "[0, 0.5, 0]" 45)" "$(point "[2, 5, 4]" 40)" \
  "$(tri "[-3, 0, -2]" "[-0.5, 0, 2]" "[-0.5, 0, -2]" red), $(tri "[-3, 0, -2]" "[-0.5, 0, 2]" "[-0.5, 0, -2]" blue),
    $(sph "[1.2, 0.8, 0]" 0.8 red), $(sph "[1.2, 0.8, 0]" 0.8 blue),
    $(tri "[-2, 1.6, -2]" "[-2, 1.6, 2]" "[4, 1.6, 0]" green)"

# S14 field-of-view extremes: the unit sphere fills the view at each fov; parallel windows
# 1e-6 and 1e6 wide on spheres of that size.
for f in 1e-4 1 90 170 179.9; do
  d=$(g "1.5 / sin($f * 3.14159265358979323846 / 360)")
  scene "S14_fov_$f" 96x96 "$(persp "$(v3 0 0 "$d")" "[0, 0, 0]" "$f")" "$(sun "[0.4, -0.5, -1]")" "$(sph "[0, 0, 0]" 1)"
done
for w in 1e-6 1e6; do
  scene "S14_parallel_$w" 96x96 "$(ortho "$(v3 0 0 "3 * $w")" "[0, 0, 0]" "1.2 * $w")" "$(sun "[0.4, -0.5, -1]")" \
    "$(sph "[0, 0, 0]" "0.5 * $w")"
done

# S15 resolution edge cases (the S01 scene at odd sizes).
for size in 1x1 1x4096 4097x3; do
  scene "S15_size_$size" "$size" "$(persp "[0, 2, 2]" "[0, 0.8, -5]" 45)" "$(s01_light 0 0 0)" "$(s01_objects 0 0 0)"
done

# S16 shadow acne: a tilted quad alone under a light at elevation E above its plane (on the
# camera's side of it, normal (0, 0.958, -0.287)): any shadowed pixel is acne. The scene
# sits at offset X (camera and all).
for x in 0 1e2 1e4 1e5; do
  for e in 0.5 10 45 89; do
    ce=$(g "cos($e * 3.14159265358979323846 / 180)"); se=$(g "sin($e * 3.14159265358979323846 / 180)")
    q1=$(v3 "$x - 10" "$x - 3" "$x - 10"); q2=$(v3 "$x + 10" "$x - 3" "$x - 10"); q3=$(v3 "$x + 10" "$x + 3" "$x + 10"); q4=$(v3 "$x - 10" "$x + 3" "$x + 10")
    scene "S16_acne_X${x}_E$e" 96x96 "$(persp "$(v3 "$x" "$x + 8" "$x + 12")" "$(v3 "$x" "$x" "$x")" 60)" \
      "$(sun "$(v3 "-$ce" "-$se * 0.95783" "$se * 0.28735")")" "$(tri "$q1" "$q2" "$q3"), $(tri "$q1" "$q3" "$q4")"
  done
done

# S17 contact shadows: a receiver and a larger occluder parallel to it at height h, the
# light straight above; a parallel camera between them looks down at the receiver. Every
# receiver pixel must be shadowed.
for x in 0 1e2 1e4; do
  for h in 1e-2 1e-3 1e-4 1e-5; do
    r1=$(v3 "$x - 1" "$x" "$x - 1"); r2=$(v3 "$x + 1" "$x" "$x - 1"); r3=$(v3 "$x + 1" "$x" "$x + 1"); r4=$(v3 "$x - 1" "$x" "$x + 1")
    o1=$(v3 "$x - 2" "$x + $h" "$x - 2"); o2=$(v3 "$x + 2" "$x + $h" "$x - 2"); o3=$(v3 "$x + 2" "$x + $h" "$x + 2"); o4=$(v3 "$x - 2" "$x + $h" "$x + 2")
    scene "S17_contact_X${x}_h$h" 64x64 "$(ortho "$(v3 "$x" "$x + $h / 2" "$x")" "$(v3 "$x" "$x - 1" "$x")" 1.8 "[0, 0, -1]")" \
      "$(sun "[0, -1, 0]")" "$(tri "$r1" "$r3" "$r2"), $(tri "$r1" "$r4" "$r3"), $(tri "$o1" "$o3" "$o2" blue), $(tri "$o1" "$o4" "$o3" blue)"
  done
done

# S18 terminator on an analytic sphere: a light sweeping across it; the sphere is convex,
# so any shadowed pixel is self-shadowing acne.
for a in 0 60 85 89.9; do
  scene "S18_terminator_$a" 96x96 "$(persp "[0, 0, 4]" "[0, 0, 0]" 40)" \
    "$(sun "$(v3 "-sin($a * 3.14159265358979323846 / 180)" 0 "-cos($a * 3.14159265358979323846 / 180)")")" "$(sph "[0, 0, 0]" 1)"
done

# S19 light placement: on a surface, inside a sphere, 1e-6 above a surface, 1e8 away.
floor="$(tri "[-5, 0, -5]" "[-5, 0, 5]" "[5, 0, 5]"), $(tri "[-5, 0, -5]" "[5, 0, 5]" "[5, 0, -5]"), $(sph "[1, 1, 0]" 0.7 red)"
scene S19_light_on_surface 96x72 "$(persp "[0, 3, 6]" "[0, 0.5, 0]" 45)" "$(point "[-1, 0, 0]" 10)" "$floor"
scene S19_light_inside_sphere 96x72 "$(persp "[0, 3, 6]" "[0, 0.5, 0]" 45)" "$(point "[1, 1, 0]" 10)" "$floor"
scene S19_light_1e-6_above 96x72 "$(persp "[0, 3, 6]" "[0, 0.5, 0]" 45)" "$(point "[-1, 1e-6, 0]" 10)" "$floor"
scene S19_light_1e8_away 96x72 "$(persp "[0, 3, 6]" "[0, 0.5, 0]" 45)" "$(point "[-1e8, 1e8, 0]" 2e16)" "$floor"
# S21 many small spheres (sphereflake-like): 2,000 spheres, r in [1e-3, 1e-1], in a unit
# cube seen from D = 2 and D = 1e3 (the field of view keeps the cube's size in the image).
# (the plan was 1e4 spheres; 2,000 keep the committed file at 0.2 MB.)
balls=$(awk 'BEGIN { srand(21); for (i = 0; i < 2000; i++) {
  r = exp(log(1e-3) + rand() * (log(1e-1) - log(1e-3)))
  printf "%s{ \"type\": \"sphere\", \"center\": [%.6f, %.6f, %.6f], \"radius\": %.6g, \"material\": \"%s\" }", (i ? ",\n    " : ""), rand() - 0.5, rand() - 0.5, rand() - 0.5, r, (i % 3 ? "white" : "red") } }')
for d in 2 1e3; do
  scene "S21_many_spheres_D$d" 128x128 "$(persp "$(v3 0 0 "$d")" "[0, 0, 0]" "2 * atan2(0.9, $d) * 180 / 3.14159265358979323846")" \
    "$(sun "[0.3, -0.6, -1]")" "$balls"
done
# S20 general quadrics: rays exactly parallel to the axes of a cylinder, paraboloid, cone
# and hyperboloid (a = 0 for the first two: the quadratic's own branch), the same axes
# tilted by 1e-6 rad (a ~ 1e-12), rays along a cone's generator (a = 0 up to rounding),
# grazing views, and ellipsoids with an axis ratio of 1e4.
ortho() { echo "\"projection\": \"parallel\", \"eye\": $1, \"look_at\": $2, \"up\": ${4:-[0, 1, 0]}, \"view_height\": $(g "$3")"; }
quadrics_along() {  # axis
  local a=$1
  echo "{ \"type\": \"cylinder\", \"center\": [-1.5, 1.5, 0], \"axis\": $a, \"radius\": 0.8, \"height\": 2, \"material\": \"red\" },
    { \"type\": \"cylinder\", \"center\": [0, 0, 0], \"axis\": $a, \"radius\": 0.5, \"height\": 2, \"capped\": false, \"material\": \"green\" },
    { \"type\": \"cone\", \"apex\": [1.5, 1.5, -1], \"axis\": $a, \"angle_deg\": 30, \"height\": 2, \"material\": \"blue\" },
    { \"type\": \"paraboloid\", \"vertex\": [-1.5, -1.5, -1], \"axis\": $a, \"radius\": 0.8, \"height\": 2, \"material\": \"white\" },
    { \"type\": \"paraboloid\", \"vertex\": [0, -2.2, -1], \"axis\": $a, \"radius\": 0.5, \"height\": 2, \"capped\": false, \"material\": \"green\" },
    { \"type\": \"hyperboloid\", \"center\": [1.5, -1.5, 0], \"axis\": $a, \"radius\": 0.4, \"end_radius\": 0.8, \"height\": 2, \"material\": \"red\" },
    { \"type\": \"box\", \"min\": [-3, -3, -1.6], \"max\": [3, 3, -1.2], \"material\": \"white\" }"
}
scene S20_axis_parallel 96x96 "$(ortho "[0, 0, 10]" "[0, 0, 0]" 6.4)" "$(sun "[0.3, -0.4, -1]")" "$(quadrics_along "[0, 0, 1]")"
scene S20_axis_tilt_1e-6 96x96 "$(ortho "[0, 0, 10]" "[0, 0, 0]" 6.4)" "$(sun "[0.3, -0.4, -1]")" "$(quadrics_along "[1e-6, 0, 1]")"
scene S20_cone_generator 96x96 "$(ortho "[-4, -4, 0]" "[0, 0, 0]" 3 "[0, 0, 1]")" "$(sun "[0.6, 0.2, -1]")" \
  "{ \"type\": \"cone\", \"apex\": [0, 0, 0], \"axis\": [0, 1, 0], \"angle_deg\": 45, \"height\": 1, \"material\": \"blue\" },
    { \"type\": \"cone\", \"apex\": [0, -0.5, 0.8], \"axis\": [0, 1, 0], \"angle_deg\": 45, \"height\": 1, \"capped\": false, \"material\": \"red\" }"
scene S20_grazing 96x96 "$(persp "[0, 0.3, 6]" "[0, 0, 0]" 30)" "$(sun "[0.2, -1, -0.3]")" \
  "{ \"type\": \"cylinder\", \"center\": [0, 0, 0], \"axis\": [1, 0, 0], \"radius\": 1, \"height\": 3, \"material\": \"red\" },
    { \"type\": \"hyperboloid\", \"center\": [0, 0, -3], \"axis\": [1, 0, 0], \"radius\": 0.5, \"end_radius\": 1.5, \"height\": 4, \"capped\": false, \"material\": \"blue\" }"
scene S20_ellipsoid_1e4_disc 96x96 "$(persp "[0, 2, 3]" "[0, 0, 0]" 45)" "$(sun "[0.3, -1, -0.5]")" \
  "{ \"type\": \"ellipsoid\", \"center\": [0, 0, 0], \"radii\": [1, 1e-4, 1], \"material\": \"red\" },
    { \"type\": \"ellipsoid\", \"center\": [0, -0.5, 0], \"radii\": [1.5, 0.1, 1.5], \"material\": \"white\" }"
scene S20_ellipsoid_1e4_needle 96x96 "$(persp "[0, 0.5, 3]" "[0, 0, 0]" 45)" "$(sun "[0.3, -1, -0.5]")" \
  "{ \"type\": \"ellipsoid\", \"center\": [0, 0.2, 0], \"radii\": [1e2, 1e-2, 1e-2], \"material\": \"red\" },
    { \"type\": \"ellipsoid\", \"center\": [0, -0.5, 0], \"radii\": [3, 0.1, 3], \"material\": \"white\" }"
# ... and a cylinder 1e6 sizes away: the precision budget must ask for f64 (as for spheres).
scene S20_far_cylinder_1e6 64x64 "$(persp "[0, 0, 1e6]" "[0, 0, 0]" "2 * atan2(2, 1e6) * 180 / 3.14159265358979323846")" \
  "$(sun "[0.3, -0.6, -1]")" \
  "{ \"type\": \"cylinder\", \"center\": [0, 0, 0], \"axis\": [0.3, 1, 0.2], \"radius\": 1, \"height\": 2.5, \"material\": \"red\" }"
# S23 infinite planes and transforms at extreme scales: a floor and a wall seen edge-on (the
# eye in the floor's plane), a floor grazed from 1e-3 above it, a floor 1e6 below the eye
# (planes need no f64 at any distance: one division from the point nearest the eye), and a
# transformed cylinder and composite at scales 1e-4 and 1e4 with the camera scaled alike.
plane() { echo "{ \"type\": \"plane\", \"point\": $1, \"normal\": $2, \"material\": \"${3:-white}\" }"; }
scene S23_plane_edge_on 96x96 "$(persp "[0, 0, 6]" "[0, 0.5, 0]" 40)" "$(point "[2, 3, 4]" 30)" \
  "$(plane "[0, 0, 0]" "[0, 1, 0]"),
    $(plane "[0, 0, -2]" "[0, 0, 1]" red),
    $(sph "[0, 1, 0]" 1 blue)"
scene S23_plane_grazing 96x96 "$(persp "[0, 1e-3, 6]" "[0, 1e-3, 0]" 30)" "$(point "[1, 2, 2]" 10)" \
  "$(plane "[0, 0, 0]" "[0, 1, 0]"),
    $(sph "[0, 0.5, 0]" 0.5 red)"
scene S23_plane_far_1e6 96x96 "$(persp "[0, 1e6, 0]" "[1e6, 0, 0]" 40)" "$(sun "[0.3, -1, 0.2]")" \
  "$(plane "[5, 0, 7]" "[0, 1, 0]"),
    $(plane "[3e6, 0, 0]" "[-1, 0.2, 0.1]" red)"
scaled() {  # NAME SCALE
  local k=$2
  scene "$1" 96x96 "$(persp "$(v3 "0.5 * $k" "1.5 * $k" "5 * $k")" "[0, 0, 0]" 45)" "$(sun "[0.3, -1, -0.5]")" \
    "{ \"type\": \"cylinder\", \"center\": [0, 0, 0], \"radius\": 0.6, \"height\": 2, \"material\": \"red\",
      \"transform\": { \"rotate_deg\": [20, 0, 60], \"scale\": $(g "$k") } },
    { \"type\": \"csg\", \"op\": \"difference\", \"material\": \"blue\",
      \"transform\": { \"rotate_deg\": [0, 35, 0], \"scale\": [$(g "$k"), $(g "0.5 * $k"), $(g "$k")], \"translate\": $(v3 "1.5 * $k" 0 "-1.5 * $k") },
      \"left\": { \"type\": \"box\", \"min\": [-0.7, -0.7, -0.7], \"max\": [0.7, 0.7, 0.7] },
      \"right\": { \"type\": \"sphere\", \"center\": [0.7, 0.7, 0.7], \"radius\": 0.8 } },
    $(plane "$(v3 0 "-1.2 * $k" 0)" "[0, 1, 0]")"
}
scaled S23_transform_scale_1e-4 1e-4
scaled S23_transform_scale_1e4 1e4
echo "wrote $(ls "$out"/*.json | wc -l) scenes to $out"
