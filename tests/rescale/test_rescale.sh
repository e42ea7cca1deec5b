#!/usr/bin/env bash
# Packing units (host/scene/scene_pack.c, docs/numerics.md §1): a scene whose size leaves
# [2^-20, 2^20] is packed in power-of-two units.
#  1. Exactness: every example scene with a far marker sphere added (size 2^21, packed at
#     2^-21) and every point light given all three attenuation terms renders the same
#     bits with --rescale on and off, on the GPU (f32) and on the CPU reference (f64), and
#     the AOV depth comes out in scene units. Power-of-two scaling is exact; a field that
#     was scaled wrongly (a quadric's constant, a transform's translation, c0 or c1 of the
#     attenuation, a parallel window) changes pixels.
#  2. Flushed subnormals: S04's sphere of radius 1e-20 (r^2 underflows f32) rendered in f32
#     by the CPU reference flushing subnormals to zero, as an NVIDIA H100 does: without
#     rescaling every pixel is NaN (the defect seen there, docs/porting.md); rescaled, no
#     value is non-finite and the image matches the f64 reference.
# Usage: test_rescale.sh VKRAYCAST SCENES_DIR EXTREMES_SCENES_DIR WORK_DIR
set -u
bin=$1 scenes=$2 extremes=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cp -r "$scenes/meshes" "$work/" || exit 1
failed=0
fail() { echo "FAIL: $*"; failed=1; }
num() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }

for name in transforms csg_meshes room quadrics hyperboloids parallel csg showcase; do
  python3 - "$scenes/$name.json" "$work/$name.json" <<'EOF' || { fail "$name: cannot make the variant"; continue; }
import json, sys
scene = json.load(open(sys.argv[1]))
for light in scene.get("lights", []):
    if light["type"] == "point":
        light["attenuation"] = [0.5, 0.25, 1]
eye = scene["camera"]["eye"]
mat = next(iter(scene["materials"]))
# Beside the eye, out of view, big enough that f32 renders it (precision_budget.h).
scene["objects"].append({"type": "sphere", "center": [eye[0] + 2**21, eye[1], eye[2]], "radius": 2**16, "material": mat})
json.dump(scene, open(sys.argv[2], "w"), indent=1)
EOF
  for backend in gpu cpu; do
    for r in on off; do
      "$bin" render "$work/$name.json" -o "$work/$name.$backend.$r.exr" --aov "$work/$name.$backend.$r.aov.exr" \
        --backend $backend --rescale $r --width 160 --height 100 --quiet --stats-json "$work/$name.$backend.$r.json" \
        2> "$work/$name.$backend.$r.stderr" || fail "$name $backend --rescale $r: exit $? ($(cat "$work/$name.$backend.$r.stderr"))"
    done
    scale=$(num packing_scale "$work/$name.$backend.on.json")
    [[ $scale == 4.76837158203125e-07 ]] || fail "$name $backend: packed at $scale, not 2^-21"
    [[ $(num packing_scale "$work/$name.$backend.off.json") == 1 ]] || fail "$name $backend: --rescale off packed at a scale"
    # f32 on the GPU: the arithmetic the rescaling is for.
    [[ $backend == cpu ]] || grep -q '"precision":[[:space:]]*"f32"' "$work/$name.$backend.on.json" ||
      fail "$name: the GPU did not render in f32 ($(cat "$work/$name.$backend.on.stderr"))"
    "$bin" compare "$work/$name.$backend.on.exr" "$work/$name.$backend.off.exr" --json > "$work/c.json" 2>/dev/null
    "$bin" compare "$work/$name.$backend.on.aov.exr" "$work/$name.$backend.off.aov.exr" --json > "$work/a.json" 2>/dev/null
    e=$(num max_error "$work/c.json") d=$(num max_depth_rel_error "$work/a.json") n=$(num max_normal_angle "$work/a.json")
    h=$(( $(num hit_mismatch "$work/a.json") + $(num object_mismatch "$work/a.json") + $(num shadow_mismatch "$work/a.json") ))
    echo "$name $backend: on/off max_error $e, depth $d, normal $n, decisions $h"
    [[ $e == 0 && $d == 0 && $n == 0 && $h == 0 ]] ||
      fail "$name $backend: rescaled render differs (colour $e, depth $d, normal $n, decisions $h)"
  done
done

s04=$extremes/S04_r1e-20_D1e-19.json
"$bin" render "$s04" -o "$work/s04.f64.exr" --aov "$work/s04.f64.aov.exr" --backend cpu --quiet || fail "S04 f64: exit $?"
for r in off on; do
  "$bin" render "$s04" -o "$work/s04.ftz.$r.exr" --aov "$work/s04.ftz.$r.aov.exr" --backend cpu --precision f32 \
    --flush-subnormals --rescale $r --quiet 2>/dev/null || fail "S04 flushed, --rescale $r: exit $?"
  "$bin" compare "$work/s04.ftz.$r.exr" "$work/s04.f64.exr" --json > "$work/c.json" 2>/dev/null
  "$bin" compare "$work/s04.ftz.$r.aov.exr" "$work/s04.f64.aov.exr" --json > "$work/a.json" 2>/dev/null
  nf=$(num nonfinite_a "$work/c.json") e=$(num max_error "$work/c.json")
  h=$(( $(num hit_mismatch "$work/a.json") + $(num object_mismatch "$work/a.json") + $(num shadow_mismatch "$work/a.json") ))
  echo "S04 r = 1e-20, f32 flushing subnormals, --rescale $r: non-finite $nf, max_error $e, decisions $h"
  if [[ $r == off ]]; then
    # The mode under test must reproduce the defect, or this test proves nothing.
    (( nf > 0 )) || fail "without rescaling the flushed f32 render has no non-finite value: the flush mode did nothing"
  else
    [[ $nf == 0 ]] || fail "rescaled, $nf non-finite values"
    awk -v e="$e" 'BEGIN { exit !(e <= 2 / 255) }' || fail "rescaled, max error $e over 2/255"
    [[ $h == 0 ]] || fail "rescaled, $h decisions differ from f64"
  fi
done
# A GPU's float modes are its own: the option is refused there, with the usage status.
"$bin" render "$s04" -o "$work/x.exr" --flush-subnormals 2> "$work/x.stderr"
[[ $? == 2 ]] && grep -q "flush-subnormals is for --backend cpu" "$work/x.stderr" || fail "--flush-subnormals on the GPU was not refused"
[[ ! -e $work/x.exr ]] || fail "a refused render wrote its output"
exit $failed
