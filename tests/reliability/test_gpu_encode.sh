#!/usr/bin/env bash
# The shader's 8-bit encoding (render --gpu-encode, host/image/levels8.h): where the output
# is an 8-bit file and nothing else needs the colours as floats, the GPU encodes each pixel
# into the file's levels and the host reads 4 bytes a pixel instead of 16. The file must be
# the one the host's own encoding writes, byte for byte, under every curve, exposure,
# quantizer, sample count, tiling, staging, region and light pass; the statistics must count
# the bytes read back; and where floats are needed (float files, AOVs, certified renders)
# the shader must not encode.
# Usage: test_gpu_encode.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"

# `same NAME SCENE EXT [render args]`: --gpu-encode auto against off, 96x64 unless the args
# say otherwise; both statistics files are kept as $work/NAME.{auto,off}.json.
same() {
  local name=$1 scene=$2 ext=$3 why=ok m
  shift 3
  for m in auto off; do
    "$bin" render "$scene" -o "$work/$name.$m.$ext" --width 96 --height 64 --quiet --gpu-encode $m \
      --stats-json "$work/$name.$m.json" "$@" 2>"$work/err" || because "$m: exit $?: $(head -c 300 "$work/err")"
  done
  [[ $why == ok ]] && { cmp -s "$work/$name.auto.$ext" "$work/$name.off.$ext" || because "the files differ"; }
  grep -q '"gpu_encoded":[[:space:]]*false' "$work/$name.off.json" || because "off: gpu_encoded is not false"
  check "$name: the same file with --gpu-encode auto and off ($*)" "$why"
}

# `bytes NAME PIXELS PER_PIXEL MODE`: readback_bytes of NAME's MODE run is PIXELS x
# PER_PIXEL plus each dispatch's status record (64 bytes: packed_status, shaders/rc_shared.h).
bytes() {
  local why=ok f=$work/$1.$4.json
  local got=$(json_num readback_bytes "$f") d=$(json_num dispatches "$f")
  local want=$(($2 * $3 + 64 * d))
  [[ $got == "$want" ]] || because "readback_bytes $got, expected $2 x $3 + 64 x $d = $want"
  check "$1 ($4): $3 bytes a pixel read back" "$why"
}

encoded() { # `encoded NAME MODE true|false`
  local why=ok
  grep -q "\"gpu_encoded\":[[:space:]]*$3" "$work/$1.$2.json" || because "gpu_encoded is not $3"
  check "$1 ($2): gpu_encoded $3" "$why"
}

same showcase "$scenes/showcase.json" png
encoded showcase auto true
bytes showcase $((96 * 64)) 4 auto
bytes showcase $((96 * 64)) 16 off
same showcase_srgb "$scenes/showcase.json" png --encoding srgb --spp 5
same room_gamma "$scenes/room.json" png --gamma 1.8 --exposure 1.5
same transforms_dark "$scenes/transforms.json" png --encoding srgb --exposure -3.25 --spp 2
same earth_truncate "$scenes/earth.json" png --quantize truncate --spp 3
same csg_bright "$scenes/csg.json" png --exposure 2
# A gamma whose level-1 threshold is subnormal (about 14 and up) is encoded on the host: a
# GPU may flush subnormals to zero. It used to stop at an assertion.
same steep_gamma "$scenes/shadows.json" png --gamma 50 --exposure 3
encoded steep_gamma auto false
# Tiles of odd sizes, through staging buffers (the copy starts past the thresholds).
same parallel_tiles "$scenes/parallel.json" png --tile 24 --staging --spp 3
bytes parallel_tiles $((96 * 64)) 4 auto
# `submits NAME MODE N`: N submits made only to copy tiles out (readback_submits). Through
# staging, a tile's last dispatch copies it in its own submit, except in light passes.
submits() {
  local why=ok got=$(json_num readback_submits "$work/$1.$2.json")
  [[ $got == "$3" ]] || because "readback_submits $got, expected $3"
  check "$1 ($2): $3 submits to copy tiles out" "$why"
}
submits parallel_tiles auto 0
submits parallel_tiles off 0
# ... and the host reads each tile while the next one's dispatch runs, the next band's
# included, except the frame's last: 12 tiles of 24 x 24 in 3 bands of 4. Each band but the
# last is written while the next band's first tile renders.
for m in auto off; do
  why=ok got=$(json_num readback_overlapped "$work/parallel_tiles.$m.json")
  [[ $got == 11 ]] || because "readback_overlapped $got, expected 11"
  got=$(json_num bands_overlapped "$work/parallel_tiles.$m.json")
  [[ $got == 2 ]] || because "bands_overlapped $got, expected 2"
  check "parallel_tiles ($m): 11 of 12 tiles and 2 of 3 bands handed on while the next renders" "$why"
done
# ... and the pixels so copied are those the host reads from mapped device memory.
for m in auto off; do
  why=ok
  "$bin" render "$scenes/parallel.json" -o "$work/parallel_direct.$m.png" --width 96 --height 64 --quiet \
    --gpu-encode $m --tile 24 --spp 3 --stats-json "$work/parallel_direct.$m.json" 2>"$work/err" ||
    because "exit $?: $(head -c 300 "$work/err")"
  cmp -s "$work/parallel_direct.$m.png" "$work/parallel_tiles.$m.png" || because "the files differ"
  # Read where the shader wrote them, a tile must be read before the next dispatch clears it.
  # A discrete GPU without host-visible device memory stages by default: there it overlaps.
  want=0
  grep -q "\"staging\":[[:space:]]*true" "$work/parallel_direct.$m.json" && want=11
  got=$(json_num readback_overlapped "$work/parallel_direct.$m.json")
  [[ $got == "$want" ]] || because "readback_overlapped $got, expected $want"
  # The band's buffers are the host's: handed on while the next band renders either way.
  got=$(json_num bands_overlapped "$work/parallel_direct.$m.json")
  [[ $got == 2 ]] || because "bands_overlapped $got, expected 2"
  check "parallel_tiles ($m): staging's file is the direct one's" "$why"
done
# What the device hid of a band's write is the write up to the dispatch's time: none where
# the dispatch takes no time (then the frame keeps the whole write), all of it where the
# dispatch outlasts it. Dispatch times injected (VKRAYCAST_FAULT=dispatch-ms), not read.
for fake in 0:0 100000:0; do
  why=ok
  VKRAYCAST_FAULT=dispatch-ms:$fake "$bin" render "$scenes/parallel.json" -o "$work/hidden.png" --width 96 \
    --height 64 --quiet --tile 24 --spp 3 --stats-json "$work/hidden.json" 2>"$work/err" ||
    because "exit $?: $(head -c 300 "$work/err")"
  python3 - "$work/hidden.json" "$fake" <<'PY' >"$work/err" 2>&1 || because "$(head -c 300 "$work/err")"
import json, sys
s, fake = json.load(open(sys.argv[1])), sys.argv[2]
written, hidden = s["band_overlapped_ms"], s["band_hidden_ms"]
if s["bands_overlapped"] != 2 or written <= 0:
    sys.exit(f"bands_overlapped {s['bands_overlapped']}, band_overlapped_ms {written}: expected 2 bands written")
want = 0.0 if fake == "0:0" else written
if abs(hidden - want) > 1e-9 * max(1.0, written):
    sys.exit(f"band_hidden_ms {hidden}, expected {want} (band_overlapped_ms {written})")
# The frame (the last, the only one) keeps what was not hidden of the bands' write.
if fake == "0:0" and s["render_wall_ms"] < written:
    sys.exit(f"render_wall_ms {s['render_wall_ms']} leaves out the {written} ms of writes no dispatch hid")
PY
  check "parallel_tiles (dispatch-ms $fake): band_hidden_ms is the write up to the dispatch's time" "$why"
done
same showcase_region "$scenes/showcase.json" png --region 10,7,90,51 --tile 32
bytes showcase_region $((80 * 44)) 4 auto
same mesh_jpeg "$scenes/mesh.json" jpg
same shadows_bmp "$scenes/shadows.json" bmp --spp 4
# Batches that grow, and light passes: a pixel is encoded in the dispatch that completes it.
same showcase_batches "$scenes/showcase.json" png --spp 16 --plan-budget 900 --tile 16
python3 - "$scenes/showcase.json" "$work/lights.json" <<'PY'
import json, random, sys
s = json.load(open(sys.argv[1]))
rng = random.Random(7)
s["lights"] = [{"type": "point", "position": [rng.uniform(-6, 6), rng.uniform(1, 8), rng.uniform(-4, 7)],
                "intensity": [0.2, 0.2, 0.2]} for _ in range(300)]
json.dump(s, open(sys.argv[2], "w"))
PY
same light_passes "$work/lights.json" png --width 32 --height 20 --plan-budget 900 --tile 8 --spp 2
why=ok
per=$(json_num lights_per_pass "$work/light_passes.auto.json")
[[ -n $per && $per -gt 0 && $per -lt 300 ]] || because "lights_per_pass $per: no passes"
check "light_passes: rendered in passes" "$why"
same light_passes_staging "$work/lights.json" png --width 32 --height 20 --plan-budget 900 --tile 8 --spp 2 --staging
submits light_passes_staging auto $(json_num tiles "$work/light_passes_staging.auto.json")

# Where the colours are needed as floats the shader does not encode.
for m in exr aov certified; do
  args=() out=$work/$m.png
  [[ $m == exr ]] && out=$work/$m.exr
  [[ $m == aov ]] && args=(--aov "$work/$m.aov.exr")
  [[ $m == certified ]] && args=(--precision certified)
  why=ok
  "$bin" render "$scenes/showcase.json" -o "$out" --width 32 --height 20 --quiet --stats-json "$work/$m.json" \
    "${args[@]}" 2>"$work/err" || because "exit $?: $(head -c 300 "$work/err")"
  grep -q '"gpu_encoded":[[:space:]]*false' "$work/$m.json" || because "gpu_encoded is not false"
  check "$m: the shader does not encode" "$why"
done

finish
