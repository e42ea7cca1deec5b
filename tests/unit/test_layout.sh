#!/usr/bin/env bash
# The C layout of every shared struct (offsetof/sizeof, printed by layout_dump) must equal
# what glslang's reflection reports for raycast.comp: member offsets, array strides, block
# sizes and binding numbers. The _Static_asserts in rc_shared.h cannot catch an assert and
# a struct edited wrongly together; this can.
set -euo pipefail
dump=$1 glslang=$2 shaders=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$dump" | sort >"$tmp/c.txt"
reflect() { "$glslang" -V --target-env vulkan1.1 -I"$shaders" -DRC_SCENE_TEXEL_BUFFERS="$1" -DRC_SCENE_TEXEL_IMAGES="${2:-0}" -q \
  --reflect-all-block-variables -o "$tmp/x.spv" "$shaders/raycast.comp"; }
{
  # Storage variant: member offsets and array strides of the scene arrays.
  reflect 0 | grep -v '\[0\]' | sed -nE \
    -e 's/^((frame|push|status|aov|level_table|scene_[a-z_]+)\.[a-z_.0-9]+): offset ([0-9]+),.*/\1 \3/p' \
    -e 's/^(levels): offset ([0-9]+),.*/\1 offset \2/p' \
    -e 's/^(Frame|Push|Status): offset -1, type [0-9a-f]+, size ([0-9]+),.*/\1 size \2/p'
  reflect 0 | sed -nE 's/^(Frame|Accum|Status|Aov|Levels): .* binding ([0-9]+),.*/\1 binding \2/p'
  reflect 0 | grep -v '\[0\]' | sed -nE 's/^(scene_[a-z_]+|aov)\.[a-z_0-9]+: offset 0,.*topLevelArrayStride ([0-9]+).*/\1 stride \2/p'
  # The object-reference and CSG program arrays are plain uint[]: its stride is on its own line.
  reflect 0 | sed -nE 's/^(scene_bvh_prims|scene_csg_program): offset 0,.*arrayStride ([0-9]+),.*/\1 stride \2/p'
  # Texel variant: the scene arrays' bindings (texel buffers are not blocks there).
  reflect 1 | sed -nE 's/^(scene_[a-z_]+): offset -1, .* binding ([0-9]+),.*/\1 binding \2/p'
  # Storage texel (image) variant: the same bindings.
  reflect 1 1 | sed -nE 's/^(scene_[a-z_]+): offset -1, .* binding ([0-9]+),.*/\1 binding \2/p'
} | sort -u >"$tmp/glsl.txt"
if ! diff -u "$tmp/c.txt" "$tmp/glsl.txt"; then
  echo "FAIL: C layout (-) differs from glslang reflection (+)" >&2
  exit 1
fi
echo "layout: $(wc -l <"$tmp/c.txt") offsets, strides, sizes and bindings agree"
