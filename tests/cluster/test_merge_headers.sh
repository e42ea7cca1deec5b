#!/usr/bin/env bash
# merge reads its parts the way render reads scenes (issue 45, class 3). The middle shard of
# a 3-shard frame is rewritten by oiiotool:
#  - in every EXR layout OpenImageIO writes that keeps the pixels (tiles of several shapes,
#    a moved data window, another display window, other lossless compressions, mip levels,
#    the channels stored in another order): the merge must equal the whole render;
#  - in layouts that change or cannot carry the pixels (half floats, an alpha channel, lossy
#    compressions): refused by name;
#  - with every field of its vkraycast header set to generated hostile values (zero, beyond
#    the largest frame, 2^32 - 1, inverted, outside the frame, malformed): exit 2 within
#    10 s, naming the file, nothing written.
# Then 3 of 48 shards: the note names the first 8 missing and counts the rest.
# Usage: test_merge_headers.sh VKRAYCAST SCENES WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool (openimageio-tools) is missing"; exit 1; }
args=(--width 64 --height 48 --spp 1 --quiet)
"$bin" render "$scenes/showcase.json" "${args[@]}" -o "$work/whole.exr" || exit 1
for i in 0 1 2; do "$bin" render "$scenes/showcase.json" "${args[@]}" --shard $i/3 -o "$work/p$i.exr" || exit 1; done
# Under the sanitizers (tools/test.sh's second pass) each kind of layout and of hostile
# value runs once: the host code is the same for the rest, which the first pass covers.
full=1
[[ -z ${ASAN_OPTIONS:-} ]] || full=0

# `layout NAME OIIOTOOL-ARGS...`: the middle part so rewritten (-o, or the last argument
# `-otex` for a mip-mapped file) merges to the whole render.
layout() {
  local name=$1 why=ok out=-o
  shift
  [[ ${*: -1} == -otex ]] && out=-otex && set -- "${@:1:$#-1}"
  oiiotool "$work/p1.exr" "$@" $out "$work/l-$name.exr" 2>"$work/err" || { check "layout $name" "oiiotool: $(cat "$work/err")"; return; }
  timeout 60 "$bin" merge "$work/p0.exr" "$work/l-$name.exr" "$work/p2.exr" -o "$work/m-$name.exr" --quiet 2>"$work/err"
  local got=$?
  [[ $got == 0 ]] || because "exit $got: $(head -c 300 "$work/err")"
  [[ $got != 0 ]] || same_pixels "$work/m-$name.exr" "$work/whole.exr" || because "the merge differs from the whole render"
  check "layout $name" "$why"
}
layout tiled-16x16 --tile 16 16
layout origin --origin +3+7
if ((full)); then
  layout tiled-7x5 --tile 7 5
  layout tiled-64x64 --tile 64 64
  layout negative-origin --origin -5-9
  layout fullsize --fullsize 100x100
  layout zip --compression zip
  layout piz --compression piz
  layout rle --compression rle
  layout none --compression none
  layout bgr-order --ch B,G,R
  layout mipmapped --tile 16 16 -otex
fi

# `refused NAME MESSAGE PART`: the merge with PART in the middle exits 2 with MESSAGE, writes nothing.
refused() {
  expect_exit2 "$1" "$work/bad.exr" "$2" timeout 10 "$bin" merge "$work/p0.exr" "$3" "$work/p2.exr" -o "$work/bad.exr"
}
oiiotool "$work/p1.exr" -d half -o "$work/half.exr" && refused "half floats" "not all 32-bit float" "$work/half.exr"
oiiotool "$work/p1.exr" --ch R,G,B,A=1.0 -o "$work/rgba.exr" && refused "alpha" "holds 4 channel(s)" "$work/rgba.exr"
lossy=(dwaa dwab b44 b44a pxr24)
((full)) || lossy=(dwaa)
for c in "${lossy[@]}"; do
  oiiotool "$work/p1.exr" --compression $c -o "$work/$c.exr" && refused "lossy $c" "compressed lossily ($c" "$work/$c.exr"
done

# Generated header values: each field of the middle part's header, each hostile value.
max=4294967295
frames=("0 48" "64 0" "65537 48" "64 65537" "$max $max" "64" "64 48 1" "-1 48" "64 x" "")
regions=("0 16 64 16" "10 16 5 32" "0 16 64 $max" "0 16 65 32" "$max 16 $max 32" "0 16 64" "0 16 64 32 7" "a b c d")
shards=("1/0" "3/3" "1/$max" "$max/$max" "1/49" "1" "1/3/3" "x/3")
n=0
hostile() { # FIELD VALUE
  n=$((n + 1))
  oiiotool "$work/p1.exr" --sattrib "vkraycast:$1" "$2" -o "$work/h$n.exr" 2>/dev/null || return
  refused "header $1 \"$2\"" "h$n.exr: " "$work/h$n.exr"
}
((full)) || frames=("${frames[4]}") regions=("${regions[1]}") shards=("${shards[2]}")
for v in "${frames[@]}"; do hostile frame "$v"; done
for v in "${regions[@]}"; do hostile region "$v"; done
for v in "${shards[@]}"; do hostile shard "$v"; done
for f in scene_hash settings device; do hostile "$f" ""; done
hostile scene_hash "0123456789abcdef"

# Many shards missing: the first 8 named, the rest counted.
for i in 0 20 47; do "$bin" render "$scenes/showcase.json" "${args[@]}" --shard $i/48 -o "$work/s$i.exr"; done
timeout 60 "$bin" merge "$work/s0.exr" "$work/s20.exr" "$work/s47.exr" -o "$work/s.exr" 2>"$work/err"
got=$? why=ok
[[ $got == 2 ]] || because "exit $got"
[[ $(grep -c "note: shard [0-9]*/48 is missing" "$work/err") == 8 ]] || because "$(grep -c "is missing" "$work/err") shards named, 8 expected"
grep -q "note: shard 1/48 is missing" "$work/err" && grep -q "note: shard 8/48 is missing" "$work/err" ||
  because "shards 1 to 8 not named first"
grep -q "and 37 more of the 48 shards are missing" "$work/err" || because "the rest not counted: $(tail -2 "$work/err")"
check "45 of 48 shards missing" "$why"
finish
