#!/usr/bin/env bash
# Whatever the CPU renders, the GPU renders: a sample too long for one dispatch (llvmpipe's
# loop cap) has its lights shaded in passes (host/gpu/gpu_plan.h). Generated scenes, the
# example scenes with many seeded random lights, each rendered on both backends with AOVs:
# the GPU's image and decisions must pass compare's gpu-vs-cpu preset (the shadow bits of the
# first 24 lights included, gathered over passes smaller than 24), the stats must show the
# passes, and in f64 the GPU must trace exactly the CPU's shadow and reflection rays (a pass
# re-traces a sample's rays but counts them once). Where a pixel cannot count the passes
# (samples x lights over 2^24), the refusal says so.
# Usage: test_light_passes.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"

# `lights SCENE N SEED OUT`: SCENE at 32x20, 1 spp, with N point and directional lights
# around it (their intensities sum to about the scene's own), its meshes copied beside it.
lights() {
  python3 - "$scenes/$1" "$2" "$3" "$4" <<'EOF'
import json, os, random, shutil, sys
src, n, seed, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
s = json.load(open(src))
rng = random.Random(seed)
s["image"] = {"width": 32, "height": 20, "samples_per_pixel": 1}
total = 60.0 / n
lights = []
for i in range(n):
    if i % 7 == 6:
        lights.append({"type": "directional", "direction": [rng.uniform(-1, 1), -1, rng.uniform(-1, 1)],
                       "intensity": [total / 40] * 3})
    else:
        lights.append({"type": "point", "position": [rng.uniform(-6, 6), rng.uniform(1, 8), rng.uniform(-4, 7)],
                       "intensity": [total * rng.uniform(0.5, 1.5) for _ in range(3)]})
s["lights"] = lights
for o in s["objects"]:
    if "file" in o:
        shutil.copy(os.path.join(os.path.dirname(src), o["file"]), os.path.dirname(out))
        o["file"] = os.path.basename(o["file"])
json.dump(s, open(out, "w"))
EOF
}

# `case NAME SCENE LIGHTS PASSES [render args]`: GPU (f32) against CPU (f64); PASSES is
# "yes" when the stats must show light passes.
case_() {
  local name=$1 scene=$2 n=$3 passes=$4 why=ok
  shift 4
  lights "$scene" "$n" "$n" "$work/$name.json"
  "$bin" render "$work/$name.json" -o "$work/$name.gpu.exr" --aov "$work/$name.gpu.aov.exr" --quiet \
    --stats-json "$work/$name.gpu.json" "$@" 2>"$work/err" || because "GPU exit $?: $(head -c 300 "$work/err")"
  # The CPU has no loop budget: --plan-budget and its value stay off its command line.
  local cpu=() skip=0 a
  for a in "$@"; do
    if ((skip)); then skip=0; elif [[ $a == --plan-budget ]]; then skip=1; else cpu+=("$a"); fi
  done
  "$bin" render "$work/$name.json" -o "$work/$name.cpu.exr" --aov "$work/$name.cpu.aov.exr" --quiet \
    --backend cpu "${cpu[@]}" 2>"$work/err" || because "CPU exit $?: $(head -c 300 "$work/err")"
  if [[ $why == ok ]]; then
    "$bin" compare "$work/$name.gpu.aov.exr" "$work/$name.cpu.aov.exr" --preset gpu-vs-cpu >"$work/cmp" 2>&1 ||
      because "compare: $(grep -E 'FAIL|error' "$work/cmp" | head -c 400)"
    local per=$(json_num lights_per_pass "$work/$name.gpu.json")
    if [[ $passes == yes ]]; then
      [[ -n $per && $per -gt 0 && $per -lt $n ]] || because "lights_per_pass $per, expected passes of fewer than $n"
    fi
  fi
  check "$name: $n lights ($*)" "$why"
}

# Under the sanitizers (tools/test.sh's second pass) the host code of every path runs on
# fewer scenes: exact small passes (brute force), halving passes over tiles (BVH), and the
# f64 count below; the numbers are gated on every scene in the first pass.
full=1
[[ -z ${ASAN_OPTIONS:-} ]] || full=0
((full)) && case_ showcase_5000 showcase.json 5000 yes --plan-budget 6144
((full)) && case_ showcase_5000_brute showcase.json 5000 yes --accel none --plan-budget 6144
# Brute force plans exact passes, so a smaller planning budget makes passes of a few lights.
# The BVH's passes start with every light and halve where the shader runs out. A budget
# under the device's is the shader's too; the cases with no other set lavapipe's own
# (6,144 on 256-bit vectors), where a GPU's 49,152 would fit all their lights at once.
case_ showcase_40_small_passes showcase.json 40 yes --accel none --plan-budget 400
case_ showcase_300_tiles showcase.json 300 yes --tile 8 --plan-budget 900
if ((full)); then
  case_ showcase_300_spp3 showcase.json 300 yes --spp 3 --plan-budget 900
  case_ showcase_depth3 showcase.json 200 yes --reflection-depth 3 --accel none --plan-budget 900
  case_ csg_500 csg.json 500 yes --plan-budget 2000
  case_ quadrics_1000 quadrics.json 1000 yes --plan-budget 6144
  case_ mesh_700 mesh.json 700 yes --plan-budget 6144
  case_ room_2000 room.json 2000 yes --shadows off --plan-budget 6144
fi

# f64 on both sides: the same rays, counted once however many passes re-trace them.
lights showcase.json 900 9 "$work/f64.json"
why=ok
"$bin" render "$work/f64.json" -o "$work/f64.gpu.exr" --precision f64 --plan-budget 700 --quiet \
  --stats-json "$work/f64.gpu.json" 2>"$work/err" || because "GPU exit $?: $(head -c 300 "$work/err")"
"$bin" render "$work/f64.json" -o "$work/f64.cpu.exr" --backend cpu --quiet --stats-json "$work/f64.cpu.json" \
  2>"$work/err" || because "CPU exit $?: $(head -c 300 "$work/err")"
for k in rays_shadow rays_reflection rays_primary; do
  g=$(json_num $k "$work/f64.gpu.json") c=$(json_num $k "$work/f64.cpu.json")
  [[ -n $g && $g == "$c" ]] || because "$k: GPU $g, CPU $c"
done
per=$(json_num lights_per_pass "$work/f64.gpu.json")
[[ -n $per && $per -gt 0 && $per -lt 900 ]] || because "lights_per_pass $per"
check "f64: the GPU in passes traces the CPU's rays exactly" "$why"

# The AOVs' digests of every sample's decisions (packed_aov.decisions): light passes trace a
# sample's rays again, pass by pass; the primary decisions count once and each shadow ray in
# its own pass, so the digests are those of the same render in one pass, bit for bit, and
# the first-sample records too (the same device and arithmetic: no decision may differ).
lights showcase.json 60 5 "$work/digest.json"
why=ok
for p in passes whole; do
  budget=()
  [[ $p == passes ]] && budget=(--plan-budget 400)
  "$bin" render "$work/digest.json" -o "$work/digest.$p.exr" --aov "$work/digest.$p.aov.exr" --spp 2 --accel none \
    --quiet --stats-json "$work/digest.$p.json" "${budget[@]}" 2>"$work/err" || because "$p: exit $?: $(head -c 300 "$work/err")"
done
per=$(json_num lights_per_pass "$work/digest.passes.json")
[[ -n $per && $per -gt 0 && $per -lt 60 ]] || because "lights_per_pass $per, expected passes"
[[ $(json_num lights_per_pass "$work/digest.whole.json") == 0 ]] || because "the whole render went in passes"
"$bin" compare "$work/digest.passes.aov.exr" "$work/digest.whole.aov.exr" --json >"$work/digest.cmp.json" 2>/dev/null
for k in sample_mismatch hit_mismatch object_mismatch shadow_mismatch; do
  [[ $(json_num $k "$work/digest.cmp.json") == 0 ]] || because "$k $(json_num $k "$work/digest.cmp.json")"
done
check "light passes: every sample's decisions are those of one pass" "$why"

# A pixel counts its progress in lights in a float, exact to 2^24: 1024 samples of 17,000
# lights cannot go in passes. The sample then runs out of the loop budget in one dispatch,
# and the refusal says why and what to change, not "objects piled up along a ray".
lights shadows.json 17000 11 "$work/17k.json"
why=ok
"$bin" render "$work/17k.json" --width 2 --height 2 --spp 1024 -o "$work/17k.exr" --quiet 2>"$work/err"
rc=$?
[[ $rc == 2 ]] || because "exit status $rc"
grep -q "1024 samples x 17000 lights is more than the 16,777,216 a pixel can count in light passes" "$work/err" ||
  because "stderr: $(head -c 400 "$work/err")"
grep -q "use fewer samples per pixel or lights" "$work/err" || because "no way out named"
! grep -q "piled up" "$work/err" || because "blames a pile of objects"
[[ ! -e $work/17k.exr ]] || because "an image was written"
check "too many samples x lights to pass: refused, the reason named" "$why"

finish
