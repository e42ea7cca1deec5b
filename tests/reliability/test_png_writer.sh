#!/usr/bin/env bash
# 8-bit RGB PNGs are written through libpng alone (host/image/png_write.c, linked into the
# binary) unless VKRAYCAST_PNG_WRITER=oiio asks for OpenImageIO's writer: both make the
# same file, byte for byte (but for gAMA above a gamma of 10, below), for every way the
# renderer writes one: the shader's levels under
# each curve and exposure, rounded or truncated; floats turned into levels on the host (a
# render with AOVs, the CPU backend); an image merged from a sharded render's parts; a
# compare heat map (one whole-image write). A render to a PNG loads no
# OpenImageIO; a full disk exits 2 and leaves the old image and no temporary.
# Usage: test_png_writer.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
size=(--width 40 --height 28 --quiet)

# `both NAME ARGS...`: runs ARGS (a vkraycast command whose output is $work/W.NAME.png)
# once with each writer W, then checks the two files are the same bytes. Exit status 1 is
# compare's answer that the images differ, not a failure.
both() {
  local name=$1 w why=ok
  shift
  for w in png oiio; do
    VKRAYCAST_PNG_WRITER=$w "$bin" "${@//@W@/$w}" >/dev/null 2>"$work/err"
    local rc=$?
    ((rc <= 1)) || because "$w: exit $rc: $(head -c 200 "$work/err")"
  done
  [[ -s $work/png.$name.png ]] || because "no file"
  cmp -s "$work/png.$name.png" "$work/oiio.$name.png" ||
    because "the files differ: $(cmp "$work/png.$name.png" "$work/oiio.$name.png" 2>&1 | head -1)"
  check "$name" "$why"
}
both linear render "$scenes/showcase.json" "${size[@]}" -o "$work/@W@.linear.png"
both srgb render "$scenes/showcase.json" "${size[@]}" --encoding srgb -o "$work/@W@.srgb.png"
both gamma render "$scenes/showcase.json" "${size[@]}" --gamma 1.7 --exposure 0.5 -o "$work/@W@.gamma.png"
both truncated render "$scenes/showcase.json" "${size[@]}" --quantize truncate -o "$work/@W@.truncated.png"
both "with AOVs (floats to levels on the host)" render "$scenes/mesh.json" "${size[@]}" \
  -o "$work/@W@.with AOVs (floats to levels on the host).png" --aov "$work/@W@.aov.exr"
both "the CPU backend" render "$scenes/mesh.json" "${size[@]}" --backend cpu --srgb -o "$work/@W@.the CPU backend.png"
for i in 0 1; do
  "$bin" render "$scenes/showcase.json" "${size[@]}" --shard $i/2 -o "$work/part$i.exr" || echo "FAIL: part $i"
done
both "a merged image (EXR parts)" merge "$work/part0.exr" "$work/part1.exr" -o "$work/@W@.a merged image (EXR parts).png" \
  --quiet
both "a heat map" compare "$work/png.linear.png" "$work/png.srgb.png" --diff "$work/@W@.a heat map.png"

# Above a gamma of 10 OpenImageIO 2.4 records gAMA as 1.0 (100000), whatever the curve;
# this writer records the curve's own, 1/gamma (2000 for 50). Every other byte is the same.
why=ok
for w in png oiio; do
  VKRAYCAST_PNG_WRITER=$w "$bin" render "$scenes/shadows.json" "${size[@]}" --gamma 50 -o "$work/$w.steep.png" \
    2>"$work/err" || because "$w: exit $?: $(head -c 200 "$work/err")"
done
gama() { od -An -tu4 --endian=big -j41 -N4 "$1" | tr -d ' '; }
[[ $(head -c 41 "$work/png.steep.png" | tail -c 4) == gAMA ]] || because "no gAMA after IHDR"
[[ $(gama "$work/png.steep.png") == 2000 ]] || because "gAMA $(gama "$work/png.steep.png"), expected 2000"
[[ $(gama "$work/oiio.steep.png") == 100000 ]] || because "OpenImageIO's gAMA $(gama "$work/oiio.steep.png")"
for off in $(cmp -l "$work/png.steep.png" "$work/oiio.steep.png" | awk '{print $1}'); do
  ((off >= 42 && off <= 49)) || { because "byte $off differs"; break; }
done
check "gamma 50: the true gAMA, every other byte OpenImageIO's" "$why"

# What the writer is for: a render to a PNG loads no OpenImageIO; a forced writer loads it.
why=ok
n=$(loads_oiio "$bin" render "$scenes/mesh.json" "${size[@]}" -o "$work/x.png")
[[ $n == 0 ]] || because "a render to a PNG loaded OpenImageIO ($n)"
n=$(VKRAYCAST_PNG_WRITER=oiio loads_oiio "$bin" render "$scenes/mesh.json" "${size[@]}" -o "$work/x.png")
[[ $n -ge 1 ]] || because "VKRAYCAST_PNG_WRITER=oiio did not load OpenImageIO"
check "a render to a PNG loads libpng alone" "$why"

# A full disk (a 16 KiB file size limit; the PNG is about 90 KB): exit status 2, the
# reason, the old image intact, no temporary.
cp "$work/png.linear.png" "$work/keep.png"
sum=$(md5sum <"$work/keep.png")
why=ok
bash -c 'ulimit -f 16; exec "$@"' _ "$bin" render "$scenes/showcase.json" --width 320 --height 200 --quiet \
  -o "$work/keep.png" 2>"$work/err"
rc=$?
[[ $rc == 2 ]] || because "exit status $rc"
grep -q "write failed: File too large" "$work/err" || because "stderr: $(head -c 300 "$work/err")"
[[ "$(md5sum <"$work/keep.png")" == "$sum" ]] || because "the old image changed"
[[ -z "$(find "$work" -name '.vkraycast-*')" ]] || because "a temporary was left"
check "a full disk: refused, the old image intact" "$why"
finish
