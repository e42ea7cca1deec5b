#!/usr/bin/env bash
# Subgroup size 4 (docs/porting.md, "Subgroups"): lavapipe built for 128-bit vectors
# (LP_NATIVE_VECTOR_WIDTH=128) runs 4 invocations per subgroup instead of 8, as narrow as
# any GPU's. The host must plan for it (loop budget 49,152 / 4, whole subgroups per
# workgroup) and the images must be bit-identical to those at width 8.
#   test_subgroup_width.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
# Only lavapipe has a vector width to set. On the GPU a build's tests were configured for
# (VKRAYCAST_TEST_DEVICE) there is nothing to test: skipped, never on lavapipe, where a
# missing device fails below.
if [[ ${VKRAYCAST_TEST_DEVICE:-llvmpipe} != llvmpipe ]]; then
  echo "SKIP: the tests run on ${VKRAYCAST_TEST_DEVICE}, not lavapipe"
  exit 77
fi

# NAME SCENE [render args...]
run() {
  local name=$1 scene=$2 why=ok
  shift 2
  for w in 128 256; do
    LP_NATIVE_VECTOR_WIDTH=$w "$bin" render "$scene" -o "$work/$name.$w.exr" --stats-json "$work/$name.$w.json" \
      --quiet --allow-outside-paths "$@" 2>"$work/$name.$w.err" || because "width $w: exit status $?: $(head -c 300 "$work/$name.$w.err")"
  done
  if [[ $why == ok ]]; then
    local s4 s8 b4 b8
    s4=$(json_num subgroup_size "$work/$name.128.json") s8=$(json_num subgroup_size "$work/$name.256.json")
    b4=$(json_num loop_budget "$work/$name.128.json") b8=$(json_num loop_budget "$work/$name.256.json")
    [[ $s4 == 4 && $s8 == 8 ]] || because "subgroup sizes $s4 and $s8, expected 4 and 8"
    [[ $b4 == 12288 && $b8 == 6144 ]] || because "loop budgets $b4 and $b8, expected 12288 and 6144"
    local shape="$(json_num workgroup_x "$work/$name.128.json")x$(json_num workgroup_y "$work/$name.128.json")"
    [[ $shape == 8x8 ]] || because "workgroup $shape at subgroup size 4, expected 8x8"
    "$bin" compare "$work/$name.128.exr" "$work/$name.256.exr" --fail 0 >"$work/$name.cmp" 2>&1 ||
      because "images differ: $(tail -3 "$work/$name.cmp" | tr '\n' ' ')"
  fi
  check "$name" "$why"
}

run showcase "$scenes/showcase.json" --width 320 --height 200
run showcase_f64_aov "$scenes/showcase.json" --width 160 --height 100 --precision f64 --aov "$work/aov.exr"
run csg "$scenes/csg.json" --width 160 --height 120
run mesh "$scenes/mesh.json" --width 160 --height 120
run transforms_brute "$scenes/transforms.json" --width 160 --height 120 --accel none --spp 8
finish
