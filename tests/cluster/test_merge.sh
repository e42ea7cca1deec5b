#!/usr/bin/env bash
# Parts of a frame merged bit for bit (docs/cluster.md): for the GPU and the CPU backend,
# f32 and f64, 1 and 16 samples per pixel, the showcase (a mirror sphere above a floor,
# sky above: rows of very different cost) is rendered whole and as 3 shards; the shards
# merged into float EXR and 8-bit PNG must equal the whole render's pixels (the PNG's
# bytes). The shards must be of uneven size (cut by cost) and cut alike whatever the
# backend and precision. Uneven --region rectangles merge too. Then every way a merge can
# be wrong is refused with exit 2, a message naming the problem, and no file written.
# Usage: test_merge.sh VKRAYCAST SCENES WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
scene=$scenes/showcase.json
size=(--width 64 --height 48)
region_of() { tr -d ' \n\t' <"$1" | sed -n 's/.*"region":\[\([0-9,]*\)\].*/\1/p'; }

# Under the sanitizers (tools/test.sh's second pass) the same code paths run on fewer
# combinations: the GPU in f32 at 16 spp and the CPU in f64 at 1 spp, plus what the
# refusals below need.
combos=()
for backend in gpu cpu; do
  for precision in f32 f64; do
    for spp in 1 16; do
      combos+=("$backend $precision $spp")
    done
  done
done
[[ -z ${ASAN_OPTIONS:-} ]] || combos=("gpu f32 1" "gpu f32 16" "gpu f64 1" "cpu f32 1" "cpu f64 1")
declare -A cuts
for combo in "${combos[@]}"; do
  read -r backend precision spp <<<"$combo"
  tag=$backend-$precision-$spp
  args=(--backend "$backend" --precision "$precision" --spp "$spp" "${size[@]}" --quiet)
  "$bin" render "$scene" "${args[@]}" -o "$work/$tag-whole.exr" || { check "$tag whole" "render failed"; continue; }
  "$bin" render "$scene" "${args[@]}" -o "$work/$tag-whole.png" || { check "$tag whole png" "render failed"; continue; }
  parts=() rows=()
  for i in 0 1 2; do
    "$bin" render "$scene" "${args[@]}" --shard $i/3 -o "$work/$tag-$i.exr" --stats-json "$work/$tag-$i.json"
    parts+=("$work/$tag-$i.exr")
    IFS=, read -r _ y0 _ y1 <<<"$(region_of "$work/$tag-$i.json")"
    rows+=($((y1 - y0)))
  done
  cuts[$tag]="${rows[*]}"
  why=ok
  [[ ${rows[0]} != "${rows[1]}" || ${rows[1]} != "${rows[2]}" ]] || why="shards of equal size (${rows[*]}): not cut by cost"
  check "$tag shards uneven (${rows[*]} rows)" "$why"
  # Parts in any order.
  "$bin" merge "${parts[2]}" "${parts[0]}" "${parts[1]}" -o "$work/$tag-merged.exr" --quiet &&
    "$bin" merge "${parts[@]}" -o "$work/$tag-merged.png" --quiet
  why=ok
  same_pixels "$work/$tag-merged.exr" "$work/$tag-whole.exr" || why="merged EXR differs from the whole render"
  check "$tag merged exr" "$why"
  why=ok
  cmp -s "$work/$tag-merged.png" "$work/$tag-whole.png" || why="merged PNG differs from the whole render"
  check "$tag merged png" "$why"
done
# The 8-bit encoding travels in the parts' headers: shards rendered with a gamma and an
# exposure merge into the PNG a whole render with them writes.
enc=(--backend cpu --precision f32 --spp 1 "${size[@]}" --quiet --gamma 2.2 --exposure 0.5)
"$bin" render "$scene" "${enc[@]}" -o "$work/gamma-whole.png"
"$bin" render "$scene" "${enc[@]}" --shard 0/2 -o "$work/gamma-0.exr"
"$bin" render "$scene" "${enc[@]}" --shard 1/2 -o "$work/gamma-1.exr"
"$bin" merge "$work/gamma-0.exr" "$work/gamma-1.exr" -o "$work/gamma-merged.png" --quiet
why=ok
cmp -s "$work/gamma-merged.png" "$work/gamma-whole.png" || why="merged PNG differs from the whole render"
cmp -s "$work/gamma-whole.png" "$work/cpu-f32-1-whole.png" && why="the gamma render equals the default one"
check "gamma 2.2 and exposure 0.5 carried through merge" "$why"
# The cuts depend on the scene only (the f32 reference's estimate), not on the backend,
# the precision or the sample count: every shard of one render cuts the frame alike.
why=ok
for tag in "${!cuts[@]}"; do [[ ${cuts[$tag]} == "${cuts[gpu-f32-1]}" ]] || why="$tag cut ${cuts[$tag]}, gpu-f32-1 ${cuts[gpu-f32-1]}"; done
check "cuts alike on every backend" "$why"

# Uneven regions (pbrt crop windows) that tile the frame, GPU f32 at 4 spp.
args=(--spp 4 "${size[@]}" --quiet)
"$bin" render "$scene" "${args[@]}" -o "$work/r-whole.exr"
regions=(0,0,64,7 0,7,13,48 13,7,64,30 13,30,50,48 50,30,64,48)
rparts=()
for r in "${regions[@]}"; do
  "$bin" render "$scene" "${args[@]}" --region "$r" -o "$work/r-$r.exr"
  rparts+=("$work/r-$r.exr")
done
"$bin" merge "${rparts[@]}" -o "$work/r-merged.exr" --quiet
why=ok
same_pixels "$work/r-merged.exr" "$work/r-whole.exr" || why="merged regions differ from the whole render"
check "regions merged" "$why"

# AOV files and band renders of shards (render --aov, --band-renders) merge like the
# images: every channel of the merged AOV file equals the whole render's bit for bit, in
# the whole render's channel order, and band render K's shards merge into its band render
# K; on the GPU in f32 and the CPU in f64 (the CPU's AOVs come from its own band path).
same_channels() { # every channel, bit for bit, and the same channel list
  idiff -fail 0 -warn 0 "$1" "$2" >/dev/null 2>&1 || return 1
  [[ $(oiiotool --info -v "$1" | grep 'channel list') == $(oiiotool --info -v "$2" | grep 'channel list') ]]
}
for combo in "gpu f32 4" "cpu f64 2"; do
  read -r backend precision spp <<<"$combo"
  tag=aov-$backend
  args=(--backend "$backend" --precision "$precision" --spp "$spp" "${size[@]}" --quiet --band-renders 2)
  "$bin" render "$scene" "${args[@]}" -o "$work/$tag-whole.exr" --aov "$work/$tag-whole-aov.exr" ||
    { check "$tag whole" "render failed"; continue; }
  for i in 0 1 2; do
    "$bin" render "$scene" "${args[@]}" --shard $i/3 -o "$work/$tag-$i.exr" --aov "$work/$tag-$i-aov.exr"
  done
  for kind in "" .band1 .band2; do
    "$bin" merge "$work/$tag-2-aov$kind.exr" "$work/$tag-0-aov$kind.exr" "$work/$tag-1-aov$kind.exr" \
      -o "$work/$tag-merged-aov$kind.exr" --quiet
    why=ok
    same_channels "$work/$tag-merged-aov$kind.exr" "$work/$tag-whole-aov$kind.exr" ||
      why="merged AOV file differs from the whole render's"
    check "$tag merged AOV$kind" "$why"
    "$bin" merge "$work/$tag-"{0,1,2}"$kind.exr" -o "$work/$tag-merged$kind.exr" --quiet
    why=ok
    same_pixels "$work/$tag-merged$kind.exr" "$work/$tag-whole$kind.exr" || why="merged image differs from the whole render"
    check "$tag merged image$kind" "$why"
  done
done
# The band renders' parts are of other (perturbed) scenes than the frame's own.
a=$work/aov-gpu
expect_merge_refusal() {
  local name=$1 want=$2
  shift 2
  expect_exit2 "$name" "$work/bad.png" "$want" "$bin" merge "$@" -o "$work/bad.png"
}
expect_merge_refusal "band render and frame" "rendered with perturb=1, but" "$a-0.exr" "$a-1.band1.exr" "$a-2.exr"
expect_merge_refusal "AOV and image" "merge the images and the AOV files separately" "$a-0-aov.exr" "$a-1.exr" "$a-2-aov.exr"
expect_merge_refusal "AOV into png" "name it .exr" "$a-0-aov.exr" "$a-1-aov.exr" "$a-2-aov.exr"
# An AOV file missing a decision channel is neither kind of part.
oiiotool "$a-1-aov.exr" --ch R,G,B,hit,object,t,N.X,N.Y,N.Z,N.Z -o "$work/aov-noshadow.exr" 2>/dev/null
expect_merge_refusal "AOV without shadow" "or the 12 channels of an AOV file" "$a-0-aov.exr" "$work/aov-noshadow.exr" "$a-2-aov.exr"

# `expect_merge_refusal NAME MESSAGE PARTS...`: exit 2, MESSAGE on stderr, no output.
expect_merge_refusal() {
  local name=$1 want=$2
  shift 2
  expect_exit2 "$name" "$work/bad.png" "$want" "$bin" merge "$@" -o "$work/bad.png"
}
p=$work/gpu-f32-1
expect_merge_refusal "missing shard" "shard 1/3 is missing" "$p-0.exr" "$p-2.exr"
expect_merge_refusal "missing region" "no part holds the pixels 13,7,64,30" "${rparts[@]:0:2}" "${rparts[@]:3}"
expect_merge_refusal "shard twice" "both hold the pixels" "$p-0.exr" "$p-1.exr" "$p-1.exr" "$p-2.exr"
expect_merge_refusal "other spp" "rendered with spp=16, but" "$p-0.exr" "$work/gpu-f32-16-1.exr" "$p-2.exr"
expect_merge_refusal "other backend" "rendered with backend=cpu, but" "$p-0.exr" "$work/cpu-f32-1-1.exr" "$p-2.exr"
expect_merge_refusal "other precision" "rendered with precision=f64, but" "$p-0.exr" "$work/gpu-f64-1-1.exr" "$p-2.exr"
expect_merge_refusal "a PNG part" "a part is 3 channels of 32-bit float" "$p-0.exr" "$work/gpu-f32-1-whole.png" "$p-2.exr"
expect_merge_refusal "a missing part" "nothing.exr: error: cannot open part: No such file or directory" "$p-0.exr" "$work/nothing.exr" "$p-2.exr"
# A shard of a changed scene (a light moved): its packed scene differs.
sed 's/"position": \[-4, 6, 5\]/"position": [-4, 6, 5.5]/' "$scene" >"$work/moved.json"
moved=$work/moved.json
"$bin" render "$moved" "${size[@]}" --spp 1 --precision f32 --quiet --shard 1/3 -o "$work/moved-1.exr" 2>/dev/null
expect_merge_refusal "other scene" "its packed scene (hash" "$p-0.exr" "$work/moved-1.exr" "$p-2.exr"
# A frame of another size.
"$bin" render "$scene" --width 64 --height 50 --spp 1 --precision f32 --quiet --shard 1/3 -o "$work/tall-1.exr"
expect_merge_refusal "other frame" "a part of a 64 x 50 frame" "$p-0.exr" "$work/tall-1.exr" "$p-2.exr"
# The output may not be one of the parts.
rm -f "$work/err"
"$bin" merge "$p-0.exr" "$p-1.exr" "$p-2.exr" -o "$p-1.exr" 2>"$work/err"
got=$? why=ok
[[ $got == 2 ]] || why="merging over a part was not refused (exit $got)"
check "output is a part" "$why"

# Render options: refused before anything renders.
expect_refusal "shard to png" "$scene" "name it .exr" --shard 0/2
rm -f "$work/o.exr"
for bad in "--shard 3/3" "--shard 1" "--region 0,0,65,48" "--region 5,5,5,9" "--shard 0/49" "--region 0,0,1,1 --shard 0/2"; do
  # shellcheck disable=SC2086
  timeout 60 "$bin" render "$scene" "${size[@]}" --quiet -o "$work/o.exr" $bad 2>"$work/err"
  got=$? why=ok
  [[ $got == 2 ]] || why="exit status $got, expected 2"
  [[ ! -e $work/o.exr ]] || why="$why; an image was written"
  check "render $bad" "$why"
done
finish
