#!/usr/bin/env bash
# The extremes suite (docs/numerics.md §7): renders each scene of a case with the default
# (robust) settings on the GPU and with the CPU f64 reference, plus four reference renders
# with inputs perturbed by a few f32 ulps (the conditioning band, §8.1), and gates the
# default's figures. Prints one markdown row per scene.
#   tests/extremes/run.sh VKRAYCAST WORKDIR CASE [RENDER_ARGS...]
# CASE is a scene-name prefix (S07, or S03_distance_1e8); RENDER_ARGS (a non-default variant) turn the gates
# off: such figures are recorded, not gated (tools/tradeoff.sh, docs/accuracy.md).
# With VKRAYCAST_DEVICE_LIMITS=minimum (a device with Vulkan 1.1's least limits and no
# f64, docs/porting.md) the gates stay, and a scene the budget pass sends to f64 must
# render in certified f32 (the uncertified samples again in f64 on the CPU) and say so.
set -euo pipefail
bin=$1 work=$2 case=$3
shift 3
variant=("$@")
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
num() { sed -n "s/^[[:space:]]*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }
str() { sed -n "s/^[[:space:]]*\"$1\":[[:space:]]*\"\([^\"]*\)\".*/\1/p" "$2" | head -1; }
failed=0
fail() { echo "FAIL $name: $*" >&2; failed=1; }

# The reference of scene $1 (CPU f64 with AOVs) and its band, cached per scene.
reference() {
  local s=$1 n
  n=$(basename "$s" .json)
  if [[ ! -f $work/$n.ref.aov.band4.exr ]]; then
    # The band in the same process: NAME.ref.bandK.exr and NAME.ref.aov.bandK.exr.
    "$bin" render "$s" -o "$work/$n.ref.exr" --aov "$work/$n.ref.aov.exr" --backend cpu --precision f64 \
      --band-renders 4 --quiet 2>/dev/null
  fi
}

shopt -s nullglob
scenes=("$here"/scenes/"$case"*.json)
[[ ${#scenes[@]} -gt 0 ]] || { echo "no scenes for $case" >&2; exit 2; }
for s in "${scenes[@]}"; do
  name=$(basename "$s" .json)
  tag=$name${variant[*]:+-$(echo "${variant[*]}" | tr -c 'a-zA-Z0-9.-' _)}${VKRAYCAST_DEVICE_LIMITS:+-$VKRAYCAST_DEVICE_LIMITS}
  reference "$s"
  ref=$name
  # S13: the translated scene against the untranslated S01 (translation invariance).
  [[ $name == S13_* ]] && { ref=S01_baseline; reference "$here/scenes/S01_baseline.json"; }
  "$bin" render "$s" -o "$work/$tag.exr" --aov "$work/$tag.aov.exr" --stats-json "$work/$tag.stats.json" --quiet \
    "${variant[@]}" 2>"$work/$tag.stderr"
  "$bin" compare "$work/$tag.aov.exr" "$work/$ref.ref.aov.exr" --band "$work/$ref.ref.aov.band1.exr" \
    --band "$work/$ref.ref.aov.band2.exr" --band "$work/$ref.ref.aov.band3.exr" --band "$work/$ref.ref.aov.band4.exr" \
    --json >"$work/$tag.cmp.json" || true
  "$bin" compare "$work/$tag.exr" "$work/$ref.ref.exr" --fail 0.008 --json >"$work/$tag.color.json" || true
  c=$work/$tag.cmp.json
  px=$(( $(num width "$c") * $(num height "$c") ))
  hits=$(num a_hits "$c") shadowed=$(num a_shadowed "$c") band=$(num band_pixels "$c")
  hit_mm=$(num hit_mismatch "$c") obj_mm=$(num object_mismatch "$c") sh_mm=$(num shadow_mismatch "$c")
  nonfinite=$(num nonfinite_a "$c") depth=$(num max_depth_rel_error "$c") normal=$(num max_normal_angle "$c")
  over=$(num pixels_over "$work/$tag.color.json")
  precision=$(str precision "$work/$tag.stats.json") f64_needed=$(num budget_needs_f64 "$work/$tag.stats.json")
  quantized=$(num budget_quantized "$work/$tag.stats.json")
  ms=$(num render_ms "$work/$tag.stats.json")
  leaks=$((px - hits))
  printf '| %s | %s | %s | %s / %s / %s | %s | %s | %s | %.3g | %.3g | %s | %s | %s%s |\n' "$name" "$precision" \
    "$band" "$hit_mm" "$obj_mm" "$sh_mm" "$over" "$leaks" "$shadowed" "$depth" "$normal" "$nonfinite" "$ms" \
    "$f64_needed" "$([[ $quantized != 0 ]] && echo ", quantized $quantized")"
  [[ ${#variant[@]} -eq 0 ]] || continue

  # Gates of the default settings (docs/accuracy.md, "The extremes suite").
  [[ $nonfinite == 0 ]] || fail "$nonfinite non-finite values in the output"
  # Without f64 a scene that needs it is rendered in certified f32, which makes the f64
  # reference's decisions: gated as well.
  # Edge-on ties between coplanar neighbours (S08 at 0 degrees and S17's parallel views put
  # pixel centres on shared edges) may go either way: both triangles are right, and the
  # t each reports differs by the GPU's division; only hits and shadows are gated there.
  [[ $name == S08_* || $name == S17_* ]] && obj_mm=0
  [[ $((hit_mm + obj_mm + sh_mm)) == 0 ]] || fail "decisions differ from the f64 reference outside the band: hit $hit_mm, object $obj_mm, shadow $sh_mm"
  # Colour: pixels over 2/255 only where a decision is ill-conditioned (+0.1 % of pixels).
  # (Not for S19: a light on a surface makes radiance beside it unbounded, where an
  # absolute threshold means nothing; its decisions and NaN count are gated.)
  [[ $name == S19_* ]] || (( over <= band + px / 1000 )) || fail "$over pixels differ by more than 2/255 (band $band)"
  case $name in
    S06_inside* | S07_* | S08_* | S09_fan* | S09_sliver* | S10_*) [[ $leaks == 0 ]] || fail "$leaks rays leaked through a closed surface" ;;
    S16_* | S18_*) [[ $shadowed == 0 ]] || fail "$shadowed pixels of shadow acne" ;;
    S17_*) [[ $shadowed == "$hits" ]] || fail "$((hits - shadowed)) of $hits pixels leak light under the occluder" ;;
  esac
  # Scenes that f32 arithmetic cannot render faithfully: the precision-budget pass must say
  # so, and --precision auto must pick f64 (lavapipe has shaderFloat64), or on a device
  # without f64 certified f32, and say so.
  case $name in
    S03_distance_1e8 | S05_ground_h1e1 | S05_ground_h1e0 | S05_ground_h1e-1 | S20_far_*)
      if [[ ${VKRAYCAST_DEVICE_LIMITS:-} == minimum ]]; then
        [[ $f64_needed -ge 1 && $precision == certified ]] && grep -q "no shaderFloat64; rendering in f32 with certified decisions" "$work/$tag.stderr" ||
          fail "without f64 the scene was not rendered certified with a note ($f64_needed, $precision)"
      else
        [[ $f64_needed -ge 1 && $precision == f64 ]] || fail "the budget pass did not ask for f64 ($f64_needed, $precision)"
      fi ;;
    # S04 at r = 1e-20: r^2 underflows f32, but the scene is packed in units of 2^-60
    # (scene_pack.c), where it is an ordinary scene.
    S01_* | S02_* | S03_distance_1e[1-5] | S04_r1e-20* | S13_* | S16_* | S17_*_h1e-[23] | S20_axis_* | S20_cone_* | S20_ellipsoid_* | S23_*)
      [[ $f64_needed == 0 && $precision == f32 ]] || fail "an ordinary scene was not left in f32 ($f64_needed, $precision)" ;;
  esac
done
exit $failed
