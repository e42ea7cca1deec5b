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
rm -rf "$work" && mkdir -p "$work" && cp -r "$scenes/meshes" "$scenes/patches" "$scenes/textures" "$work/" || exit 1
source "$(dirname "$0")/../check.sh"

names=(transforms csg_meshes room quadrics hyperboloids parallel csg showcase teapot)
# Under the sanitizers (tools/test.sh's second pass) two scenes run the packing code at a
# scale; the bit identity of the others is the first pass's.
[[ -z ${ASAN_OPTIONS:-} ]] || names=(quadrics teapot)
for name in "${names[@]}"; do
  python3 - "$scenes/$name.json" "$work/$name.json" <<'EOF' || { check "$name: the variant" "cannot be made"; continue; }
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
        2> "$work/$name.$backend.$r.stderr"
      rc=$?
      check "$name $backend --rescale $r renders" "$([[ $rc == 0 ]] && echo ok || cat "$work/$name.$backend.$r.stderr")"
    done
    scale=$(json_num packing_scale "$work/$name.$backend.on.json")
    check "$name $backend: packed at 2^-21" "$([[ $scale == 4.76837158203125e-07 ]] && echo ok || echo "packed at $scale")"
    scale=$(json_num packing_scale "$work/$name.$backend.off.json")
    check "$name $backend: --rescale off packs at 1" "$([[ $scale == 1 ]] && echo ok || echo "packed at $scale")"
    # f32 on the GPU: the arithmetic the rescaling is for.
    [[ $backend == cpu ]] || check "$name: the GPU renders in f32" "$([[ $(json_str precision "$work/$name.$backend.on.json") == f32 ]] &&
      echo ok || cat "$work/$name.$backend.on.stderr")"
    "$bin" compare "$work/$name.$backend.on.exr" "$work/$name.$backend.off.exr" --json > "$work/c.json" 2>/dev/null
    "$bin" compare "$work/$name.$backend.on.aov.exr" "$work/$name.$backend.off.aov.exr" --json > "$work/a.json" 2>/dev/null
    e=$(json_num max_error "$work/c.json") d=$(json_num max_depth_rel_error "$work/a.json")
    n=$(json_num max_normal_angle "$work/a.json")
    h=$(( $(json_num hit_mismatch "$work/a.json") + $(json_num object_mismatch "$work/a.json") + $(json_num shadow_mismatch "$work/a.json") ))
    echo "$name $backend: on/off max_error $e, depth $d, normal $n, decisions $h"
    check "$name $backend: the same bits rescaled" "$([[ $e == 0 && $d == 0 && $n == 0 && $h == 0 ]] && echo ok ||
      echo "colour $e, depth $d, normal $n, decisions $h")"
  done
done

s04=$extremes/S04_r1e-20_D1e-19.json
"$bin" render "$s04" -o "$work/s04.f64.exr" --aov "$work/s04.f64.aov.exr" --backend cpu --quiet
rc=$?
check "S04 f64 renders" "$([[ $rc == 0 ]] && echo ok || echo "exit status $rc")"
for r in off on; do
  "$bin" render "$s04" -o "$work/s04.ftz.$r.exr" --aov "$work/s04.ftz.$r.aov.exr" --backend cpu --precision f32 \
    --flush-subnormals --rescale $r --quiet 2>/dev/null
  rc=$?
  check "S04 flushed, --rescale $r renders" "$([[ $rc == 0 ]] && echo ok || echo "exit status $rc")"
  "$bin" compare "$work/s04.ftz.$r.exr" "$work/s04.f64.exr" --json > "$work/c.json" 2>/dev/null
  "$bin" compare "$work/s04.ftz.$r.aov.exr" "$work/s04.f64.aov.exr" --json > "$work/a.json" 2>/dev/null
  nf=$(json_num nonfinite_a "$work/c.json") e=$(json_num max_error "$work/c.json")
  h=$(( $(json_num hit_mismatch "$work/a.json") + $(json_num object_mismatch "$work/a.json") + $(json_num shadow_mismatch "$work/a.json") ))
  echo "S04 r = 1e-20, f32 flushing subnormals, --rescale $r: non-finite $nf, max_error $e, decisions $h"
  if [[ $r == off ]]; then
    # The mode under test must reproduce the defect, or this test proves nothing.
    check "S04 flushed unscaled has non-finite values" "$( ((nf > 0)) && echo ok || echo "none: the flush mode did nothing")"
  else
    check "S04 flushed rescaled: no non-finite value" "$([[ $nf == 0 ]] && echo ok || echo "$nf")"
    check "S04 flushed rescaled: within 2/255 of f64" "$(awk -v e="$e" 'BEGIN { exit !(e <= 2 / 255) }' && echo ok || echo "max error $e")"
    check "S04 flushed rescaled: decisions of f64" "$([[ $h == 0 ]] && echo ok || echo "$h differ")"
  fi
done
# A GPU's float modes are its own: the option is refused there, with the usage status.
expect_exit2 "--flush-subnormals on the GPU" "$work/x.exr" "flush-subnormals is for --backend cpu" \
  "$bin" render "$s04" -o "$work/x.exr" --flush-subnormals
finish
