#!/usr/bin/env bash
# uv textures (docs/scene-format.md, "Textures"), closed forms on both backends and in
# both precisions:
# - a constant texture (one texel of exactly representable colour) gives exactly the
#   untextured render with diffuse and ambient times that colour, nearest and bilinear,
#   on a sphere, a transformed sphere and a plane;
# - a two-texel texture's edge lands where the convention says: a sphere seen from +z
#   (parallel projection) is the left texel for x < 0 and the right one for x > 0 (u =
#   1/2 + atan2(x, z) / 2 pi), the top texel for y > 0 and the bottom one for y < 0;
# - a plane's texture stays where the scene puts it: the same floor seen from 10 and from
#   1000 units above, and with its point moved by (0.3, 0, 0) against a texture offset of
#   0.3, gives the same pixels;
# - repeat against clamp, and the scale, at a pixel whose texel is known;
# - a quad of two triangles with texture coordinates at its corners, as JSON triangles and
#   as an OBJ mesh's vt: the texels the convention names, and the same pixels both ways;
# - a minified texture reads its mip levels: a checker of one-texel squares, whose levels
#   past the first are all exactly grey, under a ray cone of 2 or more texels (a floor
#   under a parallel camera; a floor to the horizon, a far sphere and a quad under a
#   perspective one; a magnified floor seen in a mirror sphere, whose curvature spreads
#   the cone) gives exactly the untextured render at half the colour, and without
#   mip-mapping it does not (it aliases).
# Usage: test_textures.sh VKRAYCAST WORKDIR
set -uo pipefail
bin=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool (openimageio-tools) is missing"; exit 1; }

# pixel IMAGE X Y: "r g b" of one pixel of a float image. Each image is dumped once, under
# the hash of its bytes (a render may rewrite a file between queries): an oiiotool process
# costs about 0.4 s of CPU, loading OpenImageIO, and the test asks for over a hundred pixels.
pixel() {
  local dump=$work/dump.$(md5sum <"$1" | cut -c1-32)
  [[ -f $dump ]] || oiiotool --dumpdata "$1" >"$dump" 2>/dev/null
  sed -n "s/^ *Pixel ($2, $3): *//p" "$dump"
}

variants=("--backend gpu --precision f32" "--backend gpu --precision f64" "--backend cpu --precision f64"
  "--backend cpu --precision f32")
# Under the sanitizers (tools/test.sh's second pass) one variant: the same host code runs
# for every one; the numbers are the first pass's.
[[ -z ${ASAN_OPTIONS:-} ]] || variants=("--backend gpu --precision f32")

# 1. A constant texture.
oiiotool --create 1x1 3 --fill:color=0.5,0.25,1 0,0,1,1 -d float -o "$work/constant.exr"
objects='{ "type": "sphere", "center": [-1, 0.8, 0], "radius": 0.8, "material": "a" },
    { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "b",
      "transform": { "translate": [1.2, 0.7, 0], "rotate_deg": [20, 30, 0], "scale": [0.5, 0.7, 0.4] } },
    { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "c" }'
# The named quadrics' coordinates: a capped cylinder (side and caps), a cone, an ellipsoid
# under a transform, a composite (a sphere minus a box), on a box floor.
quadrics='{ "type": "cylinder", "center": [-1.6, 0.6, 0], "radius": 0.4, "height": 1.2, "material": "a" },
    { "type": "cone", "apex": [-0.5, 1.4, 0], "axis": [0, -1, 0.3], "angle_deg": 25, "height": 1.2, "material": "b" },
    { "type": "ellipsoid", "center": [0.5, 0.6, 0], "radii": [0.3, 0.6, 0.4], "material": "a",
      "transform": { "rotate_deg": [0, 0, 30] } },
    { "type": "csg", "op": "difference", "material": "b",
      "left": { "type": "sphere", "center": [1.6, 0.6, 0], "radius": 0.55 },
      "right": { "type": "box", "min": [1.5, 0.6, -1], "max": [2.5, 1.5, 1] } },
    { "type": "box", "min": [-3, -0.2, -2], "max": [3, 0, 1.5], "material": "c" }'
scene() { # FILE MATERIALS [OBJECTS]: by default a sphere, an ellipsoid and a floor plane
  cat >"$1" <<EOF
{ "image": { "width": 48, "height": 32 },
  "camera": { "eye": [0, 1.5, 6], "look_at": [0, 0.6, 0], "fov_y_deg": 40 },
  "materials": { $2 },
  "lights": [ { "type": "point", "position": [3, 5, 4], "intensity": [30, 30, 30] } ],
  "objects": [ ${3:-$objects} ] }
EOF
}
for shapes in spheres quadrics; do
  shape_list=$objects filters=(nearest bilinear)
  # The quadrics' coordinates feed the same sampling the spheres check with both filters.
  [[ $shapes == spheres ]] || shape_list=$quadrics filters=(nearest)
for filter in "${filters[@]}"; do
  tex="\"texture\": \"constant.exr\", \"texture_filter\": \"$filter\", \"texture_scale\": [3, 2]"
  scene "$work/textured.json" "\"a\": { \"ambient\": [0.2, 0.6, 0.4], \"diffuse\": [0.8, 0.6, 0.3], $tex },
    \"b\": { \"ambient\": [0.1, 0.1, 0.1], \"diffuse\": [0.9, 0.9, 0.9], \"specular\": [0.5, 0.5, 0.5], $tex },
    \"c\": { \"ambient\": [0.3, 0.3, 0.3], \"diffuse\": [0.7, 0.7, 0.7], $tex }" "$shape_list"
  scene "$work/plain.json" "\"a\": { \"ambient\": [0.1, 0.15, 0.4], \"diffuse\": [0.4, 0.15, 0.3] },
    \"b\": { \"ambient\": [0.05, 0.025, 0.1], \"diffuse\": [0.45, 0.225, 0.9], \"specular\": [0.5, 0.5, 0.5] },
    \"c\": { \"ambient\": [0.15, 0.075, 0.3], \"diffuse\": [0.35, 0.175, 0.7] }" "$shape_list"
  for v in "${variants[@]}"; do
    why=ok
    # shellcheck disable=SC2086
    "$bin" render "$work/textured.json" $v --quiet -o "$work/t.exr" || because "the textured render failed"
    # shellcheck disable=SC2086
    "$bin" render "$work/plain.json" $v --quiet -o "$work/p.exr" || because "the plain render failed"
    "$bin" compare "$work/t.exr" "$work/p.exr" --fail 0 --hardfail 0 >"$work/cmp" 2>&1 ||
      because "not the same pixels: $(grep -m1 'max error' "$work/cmp")"
    check "constant texture on $shapes, $filter, $v: exactly the colour times the material" "$why"
  done
done
done

# 2. Stripes on a sphere seen from +z through a parallel camera: pixel column 31 | 32 is
# x = 0, row 15 | 16 is y = 0 (64 x 32 pixels over a 4 x 2 window; the sphere, of radius
# 0.9, spans columns 18-45 and rows 2-29). The same on a vertical cylinder of that radius
# and height 1.8 (its u is 0.5 facing +z too, its v half way up at y = 0).
oiiotool --create 2x1 3 --fill:color=1,0,0 0,0,1,1 --fill:color=0,1,0 1,0,2,1 -d float -o "$work/across.exr"
oiiotool --create 1x2 3 --fill:color=0,0,1 0,0,1,1 --fill:color=1,1,0 0,1,1,2 -d float -o "$work/updown.exr"
for shape in sphere cylinder; do
for tex in across updown; do
  object='{ "type": "sphere", "center": [0, 0, 0], "radius": 0.9, "material": "m" }'
  [[ $shape == sphere ]] ||
    object='{ "type": "cylinder", "center": [0, 0, 0], "axis": [0, 1, 0], "radius": 0.9, "height": 1.8, "material": "m" }'
  cat >"$work/$tex.json" <<EOF
{ "image": { "width": 64, "height": 32 },
  "camera": { "projection": "parallel", "eye": [0, 0, 5], "look_at": [0, 0, 0], "view_height": 2 },
  "ambient_light": [1, 1, 1],
  "materials": { "m": { "ambient": [1, 1, 1], "texture": "$tex.exr", "texture_filter": "nearest" } },
  "objects": [ $object ] }
EOF
done
for v in "${variants[@]}"; do
  why=ok
  # shellcheck disable=SC2086
  "$bin" render "$work/across.json" $v --quiet -o "$work/across-out.exr" && "$bin" render "$work/updown.json" $v \
    --quiet -o "$work/updown-out.exr" || because "a render failed"
  for x in 20 26 31; do [[ $(pixel "$work/across-out.exr" $x 16) == "1.0"* ]] || because "pixel ($x, 16) is not the left texel: $(pixel "$work/across-out.exr" $x 16)"; done
  for x in 32 37 43; do [[ $(pixel "$work/across-out.exr" $x 16) == "0.0"*" 1.0"* ]] || because "pixel ($x, 16) is not the right texel: $(pixel "$work/across-out.exr" $x 16)"; done
  for y in 3 10 15; do [[ $(pixel "$work/updown-out.exr" 32 $y) == "0.0"*"0.0"*"1.0"* ]] || because "pixel (32, $y) is not the top texel: $(pixel "$work/updown-out.exr" 32 $y)"; done
  for y in 16 21 28; do [[ $(pixel "$work/updown-out.exr" 32 $y) == "1.0"*"1.0"*"0.0"* ]] || because "pixel (32, $y) is not the bottom texel: $(pixel "$work/updown-out.exr" 32 $y)"; done
  check "stripe edges at x = 0 and y = 0 on a $shape, $v" "$why"
done
done

# 3. A floor seen straight down through a parallel camera, 32 x 32 pixels over 4 x 4 units:
# a 2 x 2 checker, nearest, one repeat per 2 units (scale 0.5). Frame of the plane y = 0: u
# along +x, v along -z (docs/scene-format.md).
oiiotool --create 2x2 3 --fill:color=1,0,0 0,0,1,1 --fill:color=0,1,0 1,0,2,1 --fill:color=0,0,1 0,1,1,2 \
  --fill:color=1,1,1 1,1,2,2 -d float -o "$work/checker.exr"
floor() { # FILE EYE_HEIGHT POINT_X OFFSET_U WRAP SCALE
  cat >"$1" <<EOF
{ "image": { "width": 32, "height": 32 },
  "camera": { "projection": "parallel", "eye": [0, $2, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "view_height": 4 },
  "ambient_light": [1, 1, 1],
  "materials": { "m": { "ambient": [1, 1, 1], "texture": "checker.exr", "texture_filter": "nearest",
                        "texture_scale": [$6, $6], "texture_offset": [$4, 0], "texture_wrap": "$5" } },
  "objects": [ { "type": "plane", "point": [$3, 0, 0], "normal": [0, 1, 0], "material": "m" } ] }
EOF
}
floor "$work/f10.json" 10 0 0 repeat 0.5
floor "$work/f1000.json" 1000 0 0 repeat 0.5
floor "$work/fmoved.json" 10 0.3 0.15 repeat 0.5
floor "$work/fclamp.json" 10 0 0 clamp 0.125
for v in "${variants[@]}"; do
  why=ok
  for f in f10 f1000 fmoved fclamp; do
    # shellcheck disable=SC2086
    "$bin" render "$work/$f.json" $v --quiet -o "$work/$f.exr" || because "$f failed"
  done
  "$bin" compare "$work/f10.exr" "$work/f1000.exr" --fail 0 --hardfail 0 >/dev/null 2>&1 ||
    because "the floor moved with the eye (10 against 1000 above it)"
  "$bin" compare "$work/f10.exr" "$work/fmoved.exr" --fail 0 --hardfail 0 >/dev/null 2>&1 ||
    because "the point moved by 0.3 with an offset of 0.3 x 0.5 does not give the same floor"
  # The image's right is +x and its top -z. Pixel (i, j) is world x = (i + 0.5) / 8 - 2,
  # z = (j + 0.5) / 8 - 2, so u = x, v = -z; at scale 0.5 and repeated: pixel (4, 4) is
  # (0.28, 0.72), the left column and top row: red; (12, 4) is (0.78, 0.72): green;
  # (4, 12) is (0.28, 0.22): blue; (12, 12) is (0.78, 0.22): white.
  for want in "4 4 1.0 0.0 0.0" "12 4 0.0 1.0 0.0" "4 12 0.0 0.0 1.0" "12 12 1.0 1.0 1.0"; do
    read -r i j r g b <<<"$want"
    [[ $(pixel "$work/f10.exr" "$i" "$j") == "$r"*" $g"*" $b"* ]] || because "pixel ($i, $j) is not ($r, $g, $b): $(pixel "$work/f10.exr" "$i" "$j")"
  done
  # Clamped at scale 1/8: pixel (4, 4) is (-0.18, 0.18) -> (0, 0.18): the left column,
  # bottom row: blue.
  [[ $(pixel "$work/fclamp.exr" 4 4) == "0.0"*"0.0"*"1.0"* ]] || because "clamped pixel (4, 4) is not blue: $(pixel "$work/fclamp.exr" 4 4)"
  check "a plane's texture stays put; repeat, clamp and scale at known texels, $v" "$why"
done
# 4. A quad x, y in [-1, 1] facing +z, (u, v) = (0, 0) at its bottom left corner and (1, 1)
# at its top right, seen through a parallel camera (32 x 32 pixels over 2 x 2 units):
# pixel (i, j) is u = (i + 0.5) / 32, v = 1 - (j + 0.5) / 32. The checker above, nearest:
# (4, 4) red, (20, 4) green, (4, 20) blue, (20, 20) white. The OBJ quad says the same in
# v/vt faces.
quad_scene() { # FILE OBJECTS
  cat >"$1" <<EOF
{ "image": { "width": 32, "height": 32 },
  "camera": { "projection": "parallel", "eye": [0, 0, 5], "look_at": [0, 0, 0], "view_height": 2 },
  "ambient_light": [1, 1, 1],
  "materials": { "m": { "ambient": [1, 1, 1], "texture": "checker.exr", "texture_filter": "nearest" } },
  "objects": [ $2 ] }
EOF
}
quad_scene "$work/quad.json" '{ "type": "triangle", "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0]], "uvs": [[0, 0], [1, 0], [1, 1]], "material": "m" },
    { "type": "triangle", "vertices": [[-1, -1, 0], [1, 1, 0], [-1, 1, 0]], "uvs": [[0, 0], [1, 1], [0, 1]], "material": "m" }'
printf 'v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n' >"$work/quad.obj"
quad_scene "$work/quad_obj.json" '{ "type": "mesh", "file": "quad.obj", "material": "m" }'
for v in "${variants[@]}"; do
  why=ok
  # shellcheck disable=SC2086
  "$bin" render "$work/quad.json" $v --quiet -o "$work/quad.exr" && "$bin" render "$work/quad_obj.json" $v --quiet \
    -o "$work/quad_obj.exr" || because "a render failed"
  for want in "4 4 1.0 0.0 0.0" "20 4 0.0 1.0 0.0" "4 20 0.0 0.0 1.0" "20 20 1.0 1.0 1.0"; do
    read -r i j r g b <<<"$want"
    [[ $(pixel "$work/quad.exr" "$i" "$j") == "$r"*" $g"*" $b"* ]] || because "pixel ($i, $j) is not ($r, $g, $b): $(pixel "$work/quad.exr" "$i" "$j")"
  done
  "$bin" compare "$work/quad.exr" "$work/quad_obj.exr" --fail 0 --hardfail 0 >/dev/null 2>&1 ||
    because "the OBJ quad's vt give other pixels than the JSON quad's uvs"
  check "triangles' texture coordinates, JSON and OBJ, $v" "$why"
done
# 5. Mip levels. A 64 x 64 checker of one-texel squares: every 2 x 2 block is half white,
# so every level past the first is 0.5 exactly, as is a blend of two of them. Ambient light
# only (colour = texture x ambient), 1 sample a pixel, so a pixel's ray cone is one pixel;
# nearest, as bilinear at a half-texel offset would make level 0 grey too.
oiiotool --pattern checker:width=1:height=1:color1=0,0,0:color2=1,1,1 64x64 3 -d float -o "$work/fine.exr"
mip_scene() { # FILE CAMERA MATERIAL OBJECTS
  cat >"$1" <<EOF
{ "image": { "width": 32, "height": 32, "samples_per_pixel": 1 },
  "camera": $2,
  "ambient_light": [1, 1, 1],
  "materials": { "m": $3 },
  "objects": [ $4 ] }
EOF
}
# Straight down, parallel: a pixel is 0.125 units, 8 texels at 64 texels a unit: level 3.
# Towards the horizon, perspective: the nearest floor pixel (about 2 units away, at 30
# degrees) covers about 9 texels, farther ones more, up to the last level; the sphere (u
# around it: 64 texels over 2 pi 0.2 units) at 8 units covers about 15, the quad (64
# texels a unit) at 6 units about 12.
down='{ "projection": "parallel", "eye": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "view_height": 4 }'
horizon='{ "eye": [0, 1, 0], "look_at": [0, 0.7, -10], "fov_y_deg": 60 }'
floor_obj='{ "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "m" }'
far_objs="$floor_obj,
    { \"type\": \"sphere\", \"center\": [-0.6, 0.5, -8], \"radius\": 0.2, \"material\": \"m\" },
    { \"type\": \"triangle\", \"vertices\": [[0.5, 0.3, -6], [1.5, 0.3, -6], [1.5, 1.3, -6]], \"uvs\": [[0, 0], [1, 0], [1, 1]], \"material\": \"m\" }"
# A mirror sphere of radius 1 over a floor whose checker is magnified (a pixel is 0.125
# units, 4 texels a unit: level 0, black or white): straight down, parallel, a cone keeps
# its width until a mirror spreads it by twice the normal's turn across it, 2 w / r. At
# pixel columns 8, 9, 22 and 23 of row 16 the reflected rays meet the floor 3-5 units away
# at 15-30 degrees, a footprint of 5-17 texels: grey. A flat mirror's cone would cover 1-2
# texels there (the pixels were 1, 0.74, 0.26 and 0 before the curvature was modelled).
mip_scene "$work/mirror.json" "$down" '{ "ambient": [1, 1, 1], "texture": "fine.exr", "texture_filter": "nearest", "texture_scale": [0.0625, 0.0625] },
    "mirror": { "mirror": [1, 1, 1] }' \
  "$floor_obj, { \"type\": \"sphere\", \"center\": [0, 1, 0], \"radius\": 1, \"material\": \"mirror\" }"
for case in down horizon; do
  camera=$down objs=$floor_obj
  [[ $case == down ]] || camera=$horizon objs=$far_objs
  mip_scene "$work/mip_$case.json" "$camera" '{ "ambient": [1, 1, 1], "texture": "fine.exr", "texture_filter": "nearest" }' "$objs"
  mip_scene "$work/nomip_$case.json" "$camera" '{ "ambient": [1, 1, 1], "texture": "fine.exr", "texture_filter": "nearest", "texture_mipmap": false }' "$objs"
  mip_scene "$work/grey_$case.json" "$camera" '{ "ambient": [0.5, 0.5, 0.5] }' "$objs"
done
# Without mip-mapping the lookup is the host's packing and level 0's, the same on every
# backend: checked with the first variant alone (the suite's time, issue 48).
for v in "${variants[@]}"; do
  why=ok
  for case in down horizon; do
    kinds=(mip grey)
    [[ $v != "${variants[0]}" ]] || kinds+=(nomip)
    for f in "${kinds[@]}"; do
      # shellcheck disable=SC2086
      "$bin" render "$work/${f}_$case.json" $v --quiet -o "$work/${f}_$case.exr" || because "${f}_$case failed"
    done
    "$bin" compare "$work/mip_$case.exr" "$work/grey_$case.exr" --fail 0 --hardfail 0 >"$work/cmp" 2>&1 ||
      because "$case: the mip-mapped checker is not grey: $(grep -m1 'max error' "$work/cmp")"
    [[ $v != "${variants[0]}" ]] ||
      ! "$bin" compare "$work/nomip_$case.exr" "$work/grey_$case.exr" --fail 0.25 --hardfail 0.25 >/dev/null 2>&1 ||
      because "$case: without mip-mapping the checker is grey too (no texel of level 0 read?)"
  done
  # shellcheck disable=SC2086
  "$bin" render "$work/mirror.json" $v --quiet -o "$work/mirror.exr" || because "the mirror failed"
  for x in 8 9 22 23; do
    [[ $(pixel "$work/mirror.exr" $x 16) == "0.5000"*" 0.5000"*" 0.5000"* ]] ||
      because "the mirror's pixel ($x, 16) is not grey: $(pixel "$work/mirror.exr" $x 16)"
  done
  [[ $v == "${variants[0]}" ]] && also=", and aliases without them" || also=""
  check "a minified checker reads its mip levels (grey)$also, through a curved mirror too, $v" "$why"
done
finish
