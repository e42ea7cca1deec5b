#!/usr/bin/env bash
# The specialization constants applied on the host (render --spec-constants host, the
# default; host/gpu/spirv_specialize.h) give the pipeline the driver's own specialization
# gives (--spec-constants driver): the same image and the same decision outputs, bit for
# bit, on every example scene and under the options that change what the constants rule
# out (precisions, intersection formulas, offsets, brute force, the generic pipeline,
# samples, bounces, shadows, light buffers and passes, the 8-bit encoding); and the statistics say
# which specialized.
# Usage: test_spec_constants.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"

# `same NAME SCENE [render args]`: host against driver, 48x32, colours and decisions.
same() {
  local name=$1 scene=$2 why=ok m
  shift 2
  for m in host driver; do
    "$bin" render "$scene" -o "$work/$name.$m.exr" --aov "$work/$name.$m.aov.exr" --width 48 --height 32 --quiet \
      --spec-constants $m --stats-json "$work/$name.$m.json" "$@" 2>"$work/err" ||
      because "$m: exit $?: $(head -c 300 "$work/err")"
    [[ $(json_str spec_constants "$work/$name.$m.json") == "$m" ]] ||
      because "$m: the statistics say spec_constants $(json_str spec_constants "$work/$name.$m.json")"
  done
  if [[ $why == ok ]]; then
    same_pixels "$work/$name.host.exr" "$work/$name.driver.exr" || because "the colours differ"
    same_pixels "$work/$name.host.aov.exr" "$work/$name.driver.aov.exr" || because "the decisions differ"
  fi
  check "$name: host = driver ($*)" "$why"
}

for scene in "$scenes"/*.json; do same "$(basename "$scene" .json)" "$scene"; done
same showcase_f64 "$scenes/showcase.json" --precision f64
same mesh_certified "$scenes/mesh.json" --precision certified --certified-rerender none
same csg_certified "$scenes/csg.json" --precision certified --certified-rerender none
same showcase_formulas "$scenes/showcase.json" --sphere algebraic --triangle cramer --shadow-offset ulp
same teapot_mt "$scenes/teapot.json" --triangle moller-trumbore --shadow-offset epsilon
same quadrics_brute "$scenes/quadrics.json" --accel none --spp 3
same room_generic "$scenes/room.json" --pipeline generic
same showcase_bounce "$scenes/showcase.json" --reflection-depth 1 --shadows off --light-buffers off
same showcase_passes "$scenes/showcase.json" --accel none --plan-budget 400

# The 8-bit encoding is a constant too: PNGs byte for byte.
why=ok
for m in host driver; do
  "$bin" render "$scenes/earth.json" -o "$work/earth.$m.png" --width 48 --height 32 --quiet --spec-constants $m \
    --encoding srgb --spp 2 || because "$m failed"
done
cmp -s "$work/earth.host.png" "$work/earth.driver.png" || because "the PNGs differ"
check "earth PNG: host = driver" "$why"
finish
