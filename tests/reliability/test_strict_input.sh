#!/usr/bin/env bash
# Strict input (issue 13, class 7), generated cases:
#  - a raw NUL byte at several places in every example scene and in a .test scene, and a
#    \u0000 escape inside several strings of every example scene: exit status 2 with the
#    exact line and column, nothing written;
#  - a mesh, or a file a mesh names (a glTF buffer), outside the scene's folder by every
#    route (absolute path, "..", a link inside pointing out): refused by default with the
#    scene's file, line and field; rendered with --allow-outside-paths; a mesh inside the
#    folder (also through a link that stays inside) renders without it;
#  - values that only go wrong after parsing (beyond f32 once transformed or made relative
#    to the eye, a transform that vanishes in f32): the object's line and field.
# Usage: test_strict_input.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
export LC_ALL=C # byte columns
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
line_col() { # file offset -> "LINE:COL" of that byte (the bytes before it hold no NUL)
  local pre
  pre=$(head -c "$2" "$1"; echo x)
  pre=${pre%x}
  local newlines=${pre//[!$'\n']/} last=${pre##*$'\n'}
  echo "$((${#newlines} + 1)):$((${#last} + 1))"
}
expect_render() { # name scene [render args...]
  local name=$1 scene=$2
  shift 2
  timeout 60 "$bin" render "$scene" -o "$work/o.png" --quiet --width 16 --height 12 "$@" 2>"$work/err"
  check "$name" "$([[ $? == 0 ]] && echo ok || head -c 300 "$work/err")"
}

# NUL bytes: at 1/7, 3/7 and 5/7 of each file (whatever is there: a key, a name, a number,
# white space), replacing that byte.
printf 'size 8 8\ncamera 0 0 5 0 0 0 0 1 0 45\nambient 0.1 0.1 0.1\nsphere 0 0 0 1\ntri 0 1 2\n' >"$work/base.test"
for scene in "$scenes"/*.json "$work/base.test"; do
  name=$(basename "$scene")
  size=$(stat -c %s "$scene")
  for k in 1 3 5; do
    off=$((size * k / 7))
    # Not a newline: the expected column would be on the next line.
    while [[ $(tail -c +$((off + 1)) "$scene" | head -c 1 | od -An -c | tr -d ' ') == '\n' ]]; do off=$((off + 1)); done
    out=$work/nul_${k}_$name
    { head -c "$off" "$scene"; printf '\0'; tail -c +$((off + 2)) "$scene"; } >"$out"
    expect_refusal "NUL byte at $off of $name" "$out" "$(basename "$out"):$(line_col "$out" "$off"): error: a NUL byte"
  done
done
# \u0000 escapes: just after the opening quote of the 2nd, 5th and 9th string of each scene.
for scene in "$scenes"/*.json; do
  name=$(basename "$scene")
  for n in 2 5 9; do
    off=$(grep -bo '"' "$scene" | sed -n "$((2 * n - 1))p" | cut -d: -f1)
    [[ -n $off ]] || continue
    out=$work/esc_${n}_$name
    { head -c $((off + 1)) "$scene"; printf '\\u0000'; tail -c +$((off + 2)) "$scene"; } >"$out"
    expect_refusal "\\u0000 in string $n of $name" "$out" \
      "$(basename "$out"):$(line_col "$out" $((off + 1))): error: a \\u0000 escape"
  done
done
# A literal backslash before u0000 is not an escape of NUL.
printf '{ "image": { "width": 8, "height": 8 }, "camera": { "eye": [0, 0, 5], "look_at": [0, 0, 0] },
  "materials": { "a\\\\u0000": { "diffuse": [1, 1, 1] } },
  "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "a\\\\u0000" } ] }\n' >"$work/backslash.json"
expect_render "an escaped backslash before u0000 is a name" "$work/backslash.json"

# Files outside the scene's folder.
models=/usr/share/assimp/models
mkdir -p "$work/inside/sub" "$work/inside/links" "$work/outside"
cp "$models/OBJ/box.obj" "$work/outside/box.obj"
cp "$models/OBJ/box.obj" "$work/inside/sub/box.obj"
cp "$models/glTF2/BoxTextured-glTF/BoxTextured0.bin" "$work/outside/"
ln -sf ../../outside/box.obj "$work/inside/links/out.obj"
ln -sf ../sub/box.obj "$work/inside/links/in.obj"
ln -sf ../outside "$work/inside/outdir"
sed "s|\"BoxTextured0.bin\"|\"../outside/BoxTextured0.bin\"|" "$models/glTF2/BoxTextured-glTF/BoxTextured.gltf" \
  >"$work/inside/up_buffer.gltf"
mesh_scene() { # file -> scene naming it, mesh on line 3
  printf '{ "image": { "width": 16, "height": 12 }, "camera": { "eye": [3, 2, 5], "look_at": [0, 0, 0] },
  "materials": { "m": { "diffuse": [0.8, 0.8, 0.8] } }, "lights": [ { "type": "point", "position": [2, 4, 3], "intensity": [9, 9, 9] } ],
  "objects": [ { "type": "mesh", "file": "%s", "material": "m" } ] }\n' "$1"
}
i=0
for route in "$work/outside/box.obj" "../outside/box.obj" "links/out.obj" "outdir/box.obj" "sub/../../outside/box.obj"; do
  i=$((i + 1))
  mesh_scene "$route" >"$work/inside/out$i.json"
  expect_refusal "mesh $route: refused" "$work/inside/out$i.json" \
    "out$i.json:3:42: error: objects[0].file: lies outside the scene's folder"
  expect_render "mesh $route: --allow-outside-paths" "$work/inside/out$i.json" --allow-outside-paths
done
# (assimp joins a buffer's URI to the glTF's folder, so ".." is the way out.)
mesh_scene "up_buffer.gltf" >"$work/inside/up_buffer.json"
expect_refusal "glTF buffer ../outside: refused" "$work/inside/up_buffer.json" \
  "refused to open $work/inside/../outside/BoxTextured0.bin: it lies outside the scene's folder"
expect_render "glTF buffer ../outside: --allow-outside-paths" "$work/inside/up_buffer.json" --allow-outside-paths
for route in "sub/box.obj" "links/in.obj" "$work/inside/sub/box.obj"; do
  mesh_scene "$route" >"$work/inside/in.json"
  expect_render "mesh $route inside the folder" "$work/inside/in.json"
done

# Errors found after parsing name the object's line and field.
head='{ "image": { "width": 16, "height": 12 }, "camera": { "eye": [0, 0, 5], "look_at": [0, 0, 0] },
  "materials": { "m": { "diffuse": [1, 1, 1] } },'
late() { # name object-json expected
  printf '%s\n  "objects": [ { "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m" },\n    %s ] }\n' \
    "$head" "$2" >"$work/late.json"
  expect_refusal "$1" "$work/late.json" "late.json:4:5: error: objects[1]$3"
}
late "sphere centre beyond f32" '{ "type": "sphere", "center": [1e39, 0, 0], "radius": 1, "material": "m" }' ": its centre"
late "sphere radius squared beyond f32" '{ "type": "sphere", "center": [0, 0, 0], "radius": 1e20, "material": "m" }' ": its radius squared"
late "sphere moved beyond f32 by its transform" \
  '{ "type": "sphere", "center": [1e30, 0, 0], "radius": 1, "material": "m", "transform": { "scale": [1e10, 1, 1] } }' ": its centre"
late "sphere transform vanishing in f32" \
  '{ "type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m", "transform": { "scale": [1e300, 1, 1] } }' ": its transform"
late "triangle scaled beyond f64" \
  '{ "type": "triangle", "vertices": [[1e200, 0, 0], [0, 1, 0], [0, 0, 1]], "material": "m", "transform": { "scale": [1e200, 1, 1] } }' ": a vertex"
late "ellipsoid beyond f32" '{ "type": "ellipsoid", "center": [0, 0, 0], "radii": [1e39, 1, 1], "material": "m" }' ": its centre"
late "mesh scaled beyond f32" \
  "{ \"type\": \"mesh\", \"file\": \"$work/inside/sub/box.obj\", \"material\": \"m\", \"transform\": { \"scale\": [1e39, 1, 1] } }" \
  " (triangle 0 of 12): a vertex"
printf '%s\n  "lights": [ { "type": "point", "position": [0, 0, 0], "intensity": [1, 1, 1] },\n    { "type": "point", "position": [0, 0, 0], "intensity": [1e39, 1, 1] } ] }\n' \
  "$head" >"$work/late.json"
expect_refusal "light intensity beyond f32" "$work/late.json" "late.json:4:5: error: lights[1]: its intensity"
printf 'size 8 8\ncamera 0 0 5 0 0 0 0 1 0 45\nsphere 0 0 0 1\n  scale 1e300 1 1\n  sphere 1 0 0 1\n' >"$work/late.test"
expect_refusal ".test sphere transform vanishing in f32" "$work/late.test" "late.test:5:3: error: sphere: its transform"
finish
