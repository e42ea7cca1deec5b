#!/usr/bin/env bash
# Prepared scenes (`vkraycast prepare`, docs/cluster.md "Prepared scenes"): every example
# scene and a CSE167 .test scene, rendered from its .vkrs file (`render FILE.vkrs` and
# `render SCENE --prepared FILE.vkrs`) on the GPU and on the CPU, must give the parsed
# render's image byte for byte and its AOVs bit for bit. So must the overrides that
# re-derive the frame, --perturb and --accel none (which build the tree again), band
# renders, and shards merged across parsed and prepared renders. Then each way a file can
# be unusable (truncated, foreign, another version or layout, changed bytes, stale
# against its scene or a mesh it read, options the packing depends on) is refused with
# exit status 2, naming which, and nothing is written.
# Usage: test_prepared.sh VKRAYCAST SCENES WORKDIR
set -uo pipefail
bin=$(realpath "$1") scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
size=(--width 72 --height 48)

# same NAME RENDER_ARGS...: the parsed scene $scene and its prepared file $vkrs render the
# same PNG bytes and the same AOVs, by the file alone and (unless ALONE=1: the two differ
# only in the digest check, which the refusals below test) by --prepared.
same() {
  local name=$1 why=ok forms=(b c)
  shift
  [[ ${ALONE:-0} != 1 ]] || forms=(b)
  "$bin" render "$scene" "$@" --quiet --allow-outside-paths -o "$work/a.png" --aov "$work/a.exr" ||
    because "the parsed render failed"
  "$bin" render "$vkrs" "$@" --quiet -o "$work/b.png" --aov "$work/b.exr" --stats-json "$work/b.json" ||
    because "the prepared render failed"
  [[ ${ALONE:-0} == 1 ]] || "$bin" render "$scene" --prepared "$vkrs" "$@" --quiet -o "$work/c.png" \
    --aov "$work/c.exr" || because "the --prepared render failed"
  for x in "${forms[@]}"; do
    cmp -s "$work/a.png" "$work/$x.png" || because "$x.png differs from the parsed render's"
    same_pixels "$work/a.exr" "$work/$x.exr" || because "$x's AOVs differ from the parsed render's"
  done
  [[ $(json_str prepared "$work/b.json") == "$vkrs" ]] || because "the statistics do not name the prepared file"
  check "$name" "$why"
}

# Under the sanitizers (tools/test.sh's second pass) the same code paths run on fewer
# scenes: spheres with transforms, planes and mirrors, a smooth mesh, composites with mesh
# operands; --perturb and --accel none (the copies) on the showcase.
backends=(gpu cpu) examples=("$scenes"/*.json) bases=(showcase csg_meshes)
if [[ -n ${ASAN_OPTIONS:-} ]]; then
  backends=(gpu) bases=()
  examples=("$scenes"/{transforms,showcase,mesh,csg_meshes}.json)
fi
for scene in "${examples[@]}"; do
  name=$(basename "$scene" .json) vkrs=$work/$name.vkrs
  "$bin" prepare "$scene" -o "$vkrs" --quiet || { check "$name prepare" "prepare failed"; continue; }
  for backend in "${backends[@]}"; do ALONE=1 same "$name $backend" --backend "$backend" "${size[@]}"; done
done

# A CSE167 scene: its own `output` name and 8-bit truncation come from the summary.
cat >"$work/course.test" <<'EOF'
size 64 48
output course.png
camera 0 0 5 0 0 0 0 1 0 45
point 1 1 3 1 1 1
ambient .1 .1 .1
diffuse .8 .2 .2
specular .3 .3 .3
shininess 20
sphere 0 0 0 1
diffuse .2 .8 .2
maxverts 3
vertex -3 -1 -3
vertex 3 -1 -3
vertex 0 -1 3
tri 0 1 2
EOF
scene=$work/course.test vkrs=$work/course.vkrs
"$bin" prepare "$scene" -o "$vkrs" --quiet && same "course.test" --backend gpu
(cd "$work" && rm -f course.png && "$bin" render course.vkrs --quiet && [[ -s course.png ]])
check "course.vkrs writes the scene's own output name" "$([[ $? == 0 ]] && echo ok || echo "no course.png")"

# Overrides, the tree rebuilt, band renders: on the scenes with mirrors, composites and
# mesh operands, by the file alone and by --prepared.
for base in "${bases[@]}"; do
  scene=$scenes/$base.json vkrs=$work/$base.vkrs
  same "$base overrides" --spp 3 --width 70 --height 50 --shadow-offset ulp --reflection-depth 1 \
    --sphere algebraic --triangle cramer --shadows off
  same "$base --perturb 2" "${size[@]}" --perturb 2
  same "$base cpu f32" "${size[@]}" --backend cpu --precision f32
done
scene=$scenes/showcase.json vkrs=$work/showcase.vkrs
same "showcase --accel none" "${size[@]}" --accel none
[[ -z ${ASAN_OPTIONS:-} ]] || same "showcase --perturb 2" "${size[@]}" --perturb 2
"$bin" render "$scene" "${size[@]}" --quiet -o "$work/band.png" --band-renders 2
"$bin" render "$vkrs" "${size[@]}" --quiet -o "$work/pband.png" --band-renders 2
why=ok
for k in 1 2; do cmp -s "$work/band.band$k.png" "$work/pband.band$k.png" || because "band render $k differs"; done
check "showcase band renders" "$why"
# Shards from the parsed scene and from the file are parts of one frame.
"$bin" render "$scene" "${size[@]}" --quiet -o "$work/whole.exr"
"$bin" render "$scene" "${size[@]}" --quiet --shard 0/3 -o "$work/s0.exr"
"$bin" render "$vkrs" "${size[@]}" --quiet --shard 1/3 -o "$work/s1.exr"
"$bin" render "$scene" --prepared "$vkrs" "${size[@]}" --quiet --shard 2/3 -o "$work/s2.exr"
why=ok
"$bin" merge "$work"/s{0,1,2}.exr -o "$work/merged.exr" 2>"$work/err" || because "merge: $(head -c 300 "$work/err")"
same_pixels "$work/whole.exr" "$work/merged.exr" || because "the merged frame differs from the whole render"
check "shards of parsed and prepared renders merge" "$why"

# Refusals. The header: magic 0-7, byte order 8-11, version 12-15, layout 16-23, size
# 24-31, checksum 32-39, then the checked bytes.
good=$work/showcase.vkrs
bytes=$(stat -c %s "$good")
patched() { # OFFSET HEX-BYTES: a copy of the good file with those bytes written at OFFSET
  cp "$good" "$work/bad.vkrs"
  printf "$(sed 's/\(..\)/\\x\1/g' <<<"$2")" | dd of="$work/bad.vkrs" bs=1 seek="$1" conv=notrunc status=none
}
refused() { # NAME MESSAGE [render args]: rendering bad.vkrs is refused so
  local name=$1 want=$2
  shift 2
  expect_exit2 "$name" "$work/o.png" "$want" "$bin" render "$work/bad.vkrs" -o "$work/o.png" --quiet "$@"
}
head -c 100 "$good" >"$work/bad.vkrs" && refused "truncated header" "truncated: 100 bytes"
head -c $((bytes - 64)) "$good" >"$work/bad.vkrs" && refused "truncated body" "truncated or extended"
{ cat "$good"; printf x; } >"$work/bad.vkrs" && refused "extended" "truncated or extended"
: >"$work/bad.vkrs" && refused "empty" "truncated: 0 bytes"
cp "$scene" "$work/bad.vkrs" && refused "foreign (a JSON scene)" "foreign: it does not begin with VKRS"
patched 4 0a && refused "text-mode damage" "damaged: the bytes after VKRS"
patched 8 01020304 && refused "byte order" "the other byte order"
patched 12 63000000 && refused "version" "version: format version 99"
patched 16 00 && refused "layout" "packed structures differ"
patched $((bytes / 2)) ff && refused "a changed byte" "checksum"
patched 40 00 && refused "a changed digest" "checksum"
cp "$good" "$work/bad.vkrs" && refused "--camera-relative off" "prepare it again with --camera-relative off" \
  --camera-relative off
refused "--rescale off" "prepare it again with --rescale off" --rescale off

# Stale: the scene changed, or a mesh it reads, since the file was prepared.
mkdir -p "$work/stale/meshes"
cp "$scenes/mesh.json" "$work/stale/"
cp "$scenes"/meshes/* "$work/stale/meshes/"
"$bin" prepare "$work/stale/mesh.json" -o "$work/stale.vkrs" --quiet
"$bin" render "$work/stale/mesh.json" --prepared "$work/stale.vkrs" "${size[@]}" -o "$work/o.png" --quiet
check "unchanged scene is not stale" "$([[ $? == 0 ]] && echo ok || echo "refused")"
printf ' ' >>"$work/stale/mesh.json"
expect_exit2 "stale scene" "$work/o.png" "stale:" \
  "$bin" render "$work/stale/mesh.json" --prepared "$work/stale.vkrs" -o "$work/o.png" --quiet
cp "$scenes/mesh.json" "$work/stale/"
mesh=$(sed -n 's/.*"file": *"\([^"]*\)".*/\1/p' "$work/stale/mesh.json" | head -1)
echo "# changed" >>"$work/stale/$mesh"
expect_exit2 "stale mesh ($mesh)" "$work/o.png" "stale:" \
  "$bin" render "$work/stale/mesh.json" --prepared "$work/stale.vkrs" -o "$work/o.png" --quiet
rm "$work/stale/$mesh"
expect_exit2 "a mesh gone" "$work/o.png" "cannot check that it is the prepared form" \
  "$bin" render "$work/stale/mesh.json" --prepared "$work/stale.vkrs" -o "$work/o.png" --quiet

# Usage.
expect_exit2 "prepare -o x.png" "$work/x.png" "name the prepared scene FILE.vkrs" \
  "$bin" prepare "$scene" -o "$work/x.png"
expect_exit2 "prepare from standard input" "$work/x.vkrs" "name the file" \
  "$bin" prepare - -o "$work/x.vkrs"
expect_exit2 "a .vkrs with --prepared" "$work/o.png" "is a prepared scene already" \
  "$bin" render "$good" --prepared "$good" -o "$work/o.png"
expect_exit2 "--prepared names a non-.vkrs file" "$work/o.png" "a prepared scene is a .vkrs file" \
  "$bin" render "$scene" --prepared "$scene" -o "$work/o.png"
cp "$good" "$work/keep.vkrs"
expect_exit2 "statistics over the prepared file" "$work/o.png" "name the same file" \
  "$bin" render "$scene" --prepared "$work/keep.vkrs" -o "$work/o.png" --stats-json "$work/keep.vkrs"
cmp -s "$good" "$work/keep.vkrs"
check "the prepared file is left as it was" "$([[ $? == 0 ]] && echo ok || echo "it changed")"
expect_exit2 "prepare of a prepared scene" "$work/x2.vkrs" "is rendered by \`render\`" \
  "$bin" prepare "$good" -o "$work/x2.vkrs"
expect_exit2 "prepare over its own scene" "$work/o.png" "name the same file" \
  "$bin" prepare "$work/keep.vkrs" -o "$work/keep.vkrs"
finish
