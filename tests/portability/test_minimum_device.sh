#!/usr/bin/env bash
# The specification's minimum device (docs/porting.md, "The minimum device"): with
# VKRAYCAST_DEVICE_LIMITS=minimum the host believes the device has only Vulkan 1.1's
# required limits and no shaderFloat64 or shaderInt64. Every example scene must render
# exactly as it does in f32 on the full device; what cannot fit is refused before
# rendering with the limit and the numbers, and nothing is written. (The extremes suite
# runs on this device too: the extreme_min_* tests.)
#   test_minimum_device.sh VKRAYCAST SCENES_DIR WORKDIR GEN_MESH
set -uo pipefail
bin=$1 scenes=$2 work=$3 gen_mesh=$4
mkdir -p "$work"
source "$(dirname "$0")/../check.sh"

# Every example scene: the minimum device's image equals the full device's f32 image.
for s in "$scenes"/*.json; do
  n=$(basename "$s" .json) why=ok
  args=(--width 160 --height 100 --quiet --allow-outside-paths)
  "$bin" render "$s" -o "$work/$n.full.exr" --precision f32 "${args[@]}" 2>"$work/$n.full.err" ||
    because "full device: exit status $?"
  VKRAYCAST_DEVICE_LIMITS=minimum "$bin" render "$s" -o "$work/$n.min.exr" --stats-json "$work/$n.min.json" \
    "${args[@]}" 2>"$work/$n.min.err" || because "minimum device: exit status $?: $(head -c 300 "$work/$n.min.err")"
  if [[ $why == ok ]]; then
    [[ $(json_str precision "$work/$n.min.json") == f32 ]] || because "precision $(json_str precision "$work/$n.min.json")"
    (( $(json_num workgroup_x "$work/$n.min.json") * $(json_num workgroup_y "$work/$n.min.json") <= 128 )) ||
      because "a workgroup over maxComputeWorkGroupInvocations 128"
    "$bin" compare "$work/$n.min.exr" "$work/$n.full.exr" --fail 0 >"$work/$n.cmp" 2>&1 ||
      because "differs from the full device's f32 image: $(tail -3 "$work/$n.cmp" | tr '\n' ' ')"
  fi
  check "example $n" "$why"
done

export VKRAYCAST_DEVICE_LIMITS=minimum
# A scene that needs f64 is rendered in certified f32, with a note; the samples it cannot
# certify are rendered again in f64 on the CPU, so that every decision is the reference's.
far=$(dirname "$0")/../extremes/scenes/S03_distance_1e8.json
"$bin" render "$far" -o "$work/far.exr" --aov "$work/far.aov.exr" --stats-json "$work/far.json" --quiet 2>"$work/far.err"
rc=$? why=ok
[[ $rc == 0 ]] || because "exit status $rc"
grep -q "has no shaderFloat64; rendering in f32 with certified decisions" "$work/far.err" || because "no note: $(head -c 300 "$work/far.err")"
[[ $(json_str precision "$work/far.json") == certified ]] || because "not certified: $(json_str precision "$work/far.json")"
(( $(json_num pixels_rerendered "$work/far.json") > 0 )) || because "no pixel re-rendered"
VKRAYCAST_DEVICE_LIMITS= "$bin" render "$far" -o "$work/far.ref.exr" --backend cpu --aov "$work/far.ref.aov.exr" --quiet ||
  because "the CPU reference failed"
"$bin" compare "$work/far.aov.exr" "$work/far.ref.aov.exr" --json >"$work/far.cmp.json" 2>/dev/null
d=$(( $(json_num hit_mismatch "$work/far.cmp.json") + $(json_num object_mismatch "$work/far.cmp.json") +
      $(json_num shadow_mismatch "$work/far.cmp.json") ))
[[ $d == 0 ]] || because "$d pixels decide otherwise than the f64 reference"
check "precision auto without f64: certified, the reference's decisions" "$why"
# The 1M-triangle mesh of the benchmarks: too large for either kind of buffer there.
"$gen_mesh" 1000000 "$work/m1m.ply" >/dev/null
cat > "$work/m1m.json" <<'JSON'
{ "image": { "width": 64, "height": 48 },
  "camera": { "eye": [0, 0, 8], "look_at": [0, 0, 0], "fov_y_deg": 40 },
  "materials": { "m": { "diffuse": [0.7, 0.6, 0.5] } },
  "lights": [ { "type": "point", "position": [5, 5, 5], "intensity": [50, 50, 50] } ],
  "objects": [ { "type": "mesh", "file": "m1m.ply", "material": "m" } ] }
JSON
expect_exit2 "1M-triangle mesh" "$work/o.exr" "as storage texel buffers the triangles array needs 3000003 texels, more than maxTexelBufferElements (65536); as uniform texel buffers the triangles array needs 3000003 texels, more than maxTexelBufferElements (65536); as storage buffers 15 storage buffers, more than maxPerStageDescriptorStorageBuffers (4)" \
  "$bin" render "$work/m1m.json" -o "$work/o.exr" --quiet
expect_exit2 "storage buffers asked for" "$work/o.exr" "cannot take this scene: 15 storage buffers, more than maxPerStageDescriptorStorageBuffers (4)" \
  "$bin" render "$scenes/showcase.json" -o "$work/o.exr" --scene-buffers storage --quiet
rm -f "$work/o.exr"
"$bin" render "$scenes/showcase.json" -o "$work/o.exr" --precision f64 --quiet 2>"$work/err"
rc=$? why=ok
[[ $rc == 3 ]] || because "exit status $rc, expected 3 (the device cannot)"
grep -q "does not support shaderFloat64 and shaderInt64" "$work/err" && grep -q "${VKRAYCAST_TEST_DEVICE:-llvmpipe}" "$work/err" ||
  because "stderr: $(head -c 300 "$work/err")"
[[ ! -e $work/o.exr ]] || because "an image was written"
check "f64 asked for" "$why"
VKRAYCAST_DEVICE_LIMITS=maximum expect_exit2 "unknown limits" "$work/o.exr" "the only value is \`minimum\`" \
  "$bin" render "$scenes/showcase.json" -o "$work/o.exr" --quiet
finish
