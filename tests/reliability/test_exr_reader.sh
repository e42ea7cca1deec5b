#!/usr/bin/env bash
# OpenEXR files are read through OpenEXR alone (vkraycast-exr.so, host/image/exr_read.cpp)
# and through OpenImageIO only where that reader cannot (VKRAYCAST_EXR_READER=oiio forces
# OpenImageIO): both readers give `compare` and `merge` the same answers, on the kinds of
# EXR the renderer writes (colours, AOVs with their band, the parts of a sharded render)
# and on ones it does not (half floats in tiles, a data window off the origin, made by
# oiiotool); a compare of two EXRs loads no OpenImageIO, and a damaged file is refused
# with OpenImageIO's message, as before.
# Usage: test_exr_reader.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
size=(--width 40 --height 28 --quiet)

"$bin" render "$scenes/mesh.json" "${size[@]}" -o "$work/gpu.exr" --aov "$work/gpu.aov.exr" || echo "FAIL: render"
"$bin" render "$scenes/mesh.json" "${size[@]}" -o "$work/ref.exr" --aov "$work/ref.aov.exr" --backend cpu \
  --precision f64 --band-renders 1 || echo "FAIL: reference render"
oiiotool "$work/gpu.aov.exr" -d half --tile 16 16 -o "$work/half_tiled.aov.exr" || echo "FAIL: oiiotool half"
oiiotool "$work/gpu.exr" --crop 20x12+7+5 -o "$work/crop_a.exr" || echo "FAIL: oiiotool crop"
oiiotool "$work/ref.exr" --crop 20x12+7+5 -o "$work/crop_b.exr" || echo "FAIL: oiiotool crop"

# `same_answer NAME ARGS...`: compare ARGS --json says the same, exit status included,
# through either reader.
same_answer() {
  local name=$1 why=ok r
  shift
  for r in exr oiio; do
    VKRAYCAST_EXR_READER=$r "$bin" compare "$@" --json >"$work/$r.json" 2>"$work/$r.err"
    echo "exit $?" >>"$work/$r.json"
  done
  cmp -s "$work/exr.json" "$work/oiio.json" || because "the readers differ: $(diff "$work/exr.json" "$work/oiio.json" | head -6)"
  grep -q '"max_error"' "$work/exr.json" || because "no comparison: $(head -c 300 "$work/exr.err")"
  check "$name" "$why"
}
same_answer "colours" "$work/gpu.exr" "$work/ref.exr"
same_answer "AOVs and the band" "$work/gpu.aov.exr" "$work/ref.aov.exr" --band "$work/ref.aov.band1.exr"
same_answer "half floats in tiles" "$work/half_tiled.aov.exr" "$work/ref.aov.exr"
same_answer "a data window off the origin" "$work/crop_a.exr" "$work/crop_b.exr"

# The parts of a sharded render, merged through either reader: the same image.
for i in 0 1 2; do
  "$bin" render "$scenes/showcase.json" "${size[@]}" --shard $i/3 -o "$work/part$i.exr" --aov "$work/part$i.aov.exr" ||
    echo "FAIL: part $i"
done
why=ok
for r in exr oiio; do
  VKRAYCAST_EXR_READER=$r "$bin" merge "$work"/part{0,1,2}.exr -o "$work/merged_$r.exr" --quiet || because "$r: merge failed"
  VKRAYCAST_EXR_READER=$r "$bin" merge "$work"/part{0,1,2}.aov.exr -o "$work/merged_$r.aov.exr" --quiet ||
    because "$r: AOV merge failed"
done
same_pixels "$work/merged_exr.exr" "$work/merged_oiio.exr" || because "the merged colours differ"
same_pixels "$work/merged_exr.aov.exr" "$work/merged_oiio.aov.exr" || because "the merged AOVs differ"
check "merge: the same image through either reader" "$why"

# What the fast reader is for: no OpenImageIO in a compare of EXRs; a forced one loads it.
why=ok
n=$(loads_oiio "$bin" compare "$work/gpu.aov.exr" "$work/ref.aov.exr")
[[ $n == 0 ]] || because "compare of two EXRs loaded OpenImageIO ($n)"
n=$(VKRAYCAST_EXR_READER=oiio loads_oiio "$bin" compare "$work/gpu.aov.exr" "$work/ref.aov.exr")
[[ $n -ge 1 ]] || because "VKRAYCAST_EXR_READER=oiio did not load OpenImageIO"
check "compare of two EXRs loads OpenEXR alone" "$why"

# A damaged EXR: OpenEXR's reader gives up, OpenImageIO's refuses it, in its own words.
head -c 600 "$work/gpu.exr" >"$work/cut.exr"
why=ok
for r in exr oiio; do
  VKRAYCAST_EXR_READER=$r "$bin" compare "$work/cut.exr" "$work/gpu.exr" >/dev/null 2>"$work/$r.err"
  echo "exit $?" >>"$work/$r.err"
done
cmp -s "$work/exr.err" "$work/oiio.err" || because "the refusals differ: $(diff "$work/exr.err" "$work/oiio.err" | head -4)"
grep -q "exit 2" "$work/exr.err" && grep -q "cannot read image" "$work/exr.err" || because "$(cat "$work/exr.err")"
check "a damaged EXR: OpenImageIO's refusal" "$why"
finish
