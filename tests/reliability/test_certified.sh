#!/usr/bin/env bash
# --precision certified is sound (docs/numerics.md §10): on example scenes (quadrics.json: every
# bounded quadric, a mirror box under them; dollhouse.json: a one-sided mesh, t-min offsets),
# on composites with tied and nearly coincident surfaces, on Bezier patches (the teapot, and the
# teapot at a thousandth of its size far away), and on the
# extremes scenes where plain f32 makes other decisions than the f64 reference (cracks between
# triangles, a fan, a huge triangle, contact shadows, a far cylinder, a crowd of far spheres
# and of far ellipsoids, a grazing ground plane), every pixel the GPU's f32 pass certifies has the f64 CPU
# reference's hit, object and shadow decisions (compare's certified_mismatch, on the
# frames whose uncertified pixels were re-rendered: that leaves the certified ones as the
# f32 pass made them), and the CPU twin's pass too; and every pixel the reference's
# conditioning band (--band-renders 4: inputs moved by a few ulps) shows flipping is
# uncertified (compare's certified_in_band). The test is shown able to fail: with the
# bound injected as zero (--certified-bound zero) the same comparisons count broken
# certificates, or certified pixels in the band, on at least 10 of these scenes (10 when
# this was written; f32 makes the reference's decisions on dollhouse, the composites and the
# near teapot, so a zero bound breaks none there). (Halved, it breaks none: the bounds are
# conservative by more than 2 wherever f32 differs; docs/numerics.md §10.) With the default
# re-render, on either backend, every decision is the reference's, and the pixels
# re-rendered are the uncertified ones. With the f64 shader re-rendering them on the GPU
# (--certified-rerender gpu; on the mesh through staging buffers and small tiles, the path
# of a discrete GPU) the decisions differ from the reference's on no more pixels than the
# GPU's own f64 render's do (none on the example scenes; 1 of the crowd of ellipsoids).
# Usage: test_certified.sh VKRAYCAST SCENES_DIR EXTREMES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 extremes=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"

render() { "$bin" render "$@" -q --allow-outside-paths 2>>"$work/err"; }
# counts A B [compare args] -> "uncertified_pixels certified_mismatch decisions
# certified_in_band band_pixels" of A against B (the last two with --band).
counts() {
  "$bin" compare "$@" --json >"$work/cmp.json" 2>/dev/null
  # Decisions: the first sample's (hit, object, shadow) and, through the digests of every
  # sample's decisions (the AOV's `decisions` channel), the other samples' and bounces'.
  local d=$(( $(json_num hit_mismatch "$work/cmp.json") + $(json_num object_mismatch "$work/cmp.json") +
             $(json_num shadow_mismatch "$work/cmp.json") + $(json_num sample_mismatch "$work/cmp.json" | grep . || echo 0) ))
  echo "$(json_num uncertified_pixels "$work/cmp.json") $(json_num certified_mismatch "$work/cmp.json") $d" \
    "$(json_num certified_in_band "$work/cmp.json") $(json_num band_pixels "$work/cmp.json")"
}

# S21's 2,000 far spheres made ellipsoids, each squashed and turned its own way: transformed
# spheres (tested in object space) where f32 differs from f64 on some 40 pixels.
python3 - "$extremes/S21_many_spheres_D1e3.json" "$work/ellipsoids.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["objects"] = [{"type": "sphere", "center": [0, 0, 0], "radius": o["radius"], "material": o["material"],
                 "transform": {"translate": o["center"], "rotate_deg": [i * 37 % 180, i * 53 % 180, i * 71 % 180],
                               "scale": [1, 0.4 + 0.2 * (i % 4), 1.3]}} for i, o in enumerate(s["objects"])]
json.dump(s, open(sys.argv[2], "w"))
PY

# Composites at their hardest: a box minus a box flush with its top face and two boxes that
# touch (interval ends tied exactly), and minus a cylinder 1e-7 wider than the one it cuts;
# two spheres 1e-7 apart intersected; two boxes 1.2e-7 apart joined; a mirror sphere cut by
# a box; a cube mesh joined with the box it coincides with, and a torus mesh cut by a box
# (mesh operands: crossings near edges and at silhouettes); all standing on the ground plane
# their bottoms lie in (docs/numerics.md §10).
cp "$scenes/meshes/cube.obj" "$scenes/meshes/torus.obj" "$work/"
python3 - "$work/composites.json" <<'PY'
import json, sys
def box(lo, hi): return {"type": "box", "min": lo, "max": hi}
def csg(op, left, right, material, translate, turn=(0, 0, 0)):
    return {"type": "csg", "op": op, "left": left, "right": right, "material": material,
            "transform": {"translate": translate, "rotate_deg": list(turn)}}
objects = [
    csg("difference", box([-1, -1, -1], [1, 1, 1]), box([-0.5, -0.5, 0], [0.5, 0.5, 1]), "mirror", [-2, 0, 0]),
    csg("union", box([-1, -1, -1], [0, 1, 1]), box([0, -1, -1], [1, 1, 1]), "blue", [1, 0, 0], (0, 30, 0)),
    csg("intersection", {"type": "sphere", "center": [0, 0, 0], "radius": 1},
        {"type": "sphere", "center": [1e-7, 0, 0], "radius": 1 + 1e-7}, "green", [4, 0, 0]),
    csg("difference", {"type": "sphere", "center": [0, 0, 0], "radius": 1.2}, box([0, 0, -2], [2, 2, 2]), "mirror",
        [1, 0, 3], (10, 20, 0)),
    csg("union", box([-1, -1, -1], [0, 1, 1]), box([1.2e-7, -1, -1], [1, 1, 1]), "green", [2.5, 0, -2.5], (0, -40, 0)),
    csg("difference", {"type": "cylinder", "center": [0, 0, 0], "radius": 0.8, "height": 2},
        {"type": "cylinder", "center": [0, 0, 0], "radius": 0.8000001, "height": 1}, "blue", [-0.5, 0, -2.5]),
    csg("union", {"type": "mesh", "file": "cube.obj"}, box([-1, -1, -1], [1, 1, 1]), "blue", [-3, 0, 2.5],
        (0, 15, 0)),
    csg("intersection", {"type": "mesh", "file": "torus.obj"}, box([-2, -1, -0.6], [2, 1, 2]), "green",
        [4, 0.3, 2.5], (60, 0, 0)),
    {"type": "plane", "point": [0, -1, 0], "normal": [0, 1, 0], "material": "white"}]
json.dump({"version": 1, "image": {"width": 160, "height": 120, "samples_per_pixel": 1},
           "camera": {"eye": [0, 3.5, 7.5], "look_at": [1, 0, 1], "up": [0, 1, 0], "fov_y_deg": 55},
           "background": [0, 0, 0], "ambient_light": [1, 1, 1],
           "materials": {"white": {"ambient": [0.05] * 3, "diffuse": [0.8] * 3},
                         "mirror": {"ambient": [0.05, 0, 0], "diffuse": [0.8, 0.1, 0.1], "specular": [0.3] * 3,
                                    "shininess": 30, "mirror": 0.3},
                         "blue": {"ambient": [0, 0, 0.05], "diffuse": [0.1, 0.1, 0.8]},
                         "green": {"ambient": [0, 0.05, 0], "diffuse": [0.1, 0.8, 0.1]}},
           "lights": [{"type": "point", "position": [2, 6, 6], "intensity": [40, 40, 40]},
                      {"type": "directional", "direction": [-0.3, -1, -0.2], "intensity": [0.5] * 3}],
           "objects": objects}, open(sys.argv[1], "w"))
PY

# Bezier patches (docs/numerics.md §10: Newton's run followed, Kantorovich's theorem): the
# course's teapot at a ninth of its pixels, and the teapot at a thousandth of its size 40
# units away, where f32 makes other decisions than f64 (tests/patches).
python3 - "$scenes" "$work" <<'PY'
import json, os, sys
scenes, work = sys.argv[1:]
s = json.load(open(os.path.join(scenes, "teapot.json")))
s["image"].update(width=160, height=120)
for m in s["materials"].values():
    if "texture" in m: m["texture"] = os.path.join(scenes, m["texture"])
for o in s["objects"]:
    if "file" in o: o["file"] = os.path.join(scenes, o["file"])
json.dump(s, open(os.path.join(work, "teapot.json"), "w"))
far = {"image": {"width": 64, "height": 48},
       "camera": {"eye": [0, 0.005, 40], "look_at": [0, 0.0015, 0], "fov_y_deg": 0.01},
       "materials": {"m": {"diffuse": [0.8, 0.8, 0.8]}},
       "lights": [{"type": "directional", "direction": [0.3, -1, -0.5], "intensity": [1, 1, 1]}],
       "objects": [{"type": "bezier_patches", "file": os.path.join(scenes, "patches/teapot.bpt"), "material": "m",
                    "transform": {"rotate_deg": [-90, 0, 0], "scale": [0.001, 0.001, 0.001]}}]}
json.dump(far, open(os.path.join(work, "far_teapot.json"), "w"))
PY

faulted=0
for s in "$scenes/mesh.json" "$scenes/showcase.json" "$scenes/shadows.json" "$scenes/earth.json" "$scenes/quadrics.json" \
         "$scenes/dollhouse.json" "$work/ellipsoids.json" "$work/composites.json" \
         "$extremes/S05_ground_h1e0.json" "$extremes/S08_cracks_0deg_at_0.json" "$extremes/S09_fan_1000.json" \
         "$extremes/S11_huge_triangle_1e7.json" "$extremes/S17_contact_X0_h1e-2.json" \
         "$extremes/S20_far_cylinder_1e6.json" "$extremes/S21_many_spheres_D1e3.json" \
         "$work/teapot.json" "$work/far_teapot.json"; do
  n=$(basename "$s" .json)
  why=ok
  render "$s" -o "$work/$n.ref.exr" --backend cpu --precision f64 --aov "$work/$n.ref.aov.exr" --band-renders 4 ||
    because "the f64 render failed"
  render "$s" -o "$work/$n.f32.exr" --precision f32 --aov "$work/$n.f32.aov.exr" || because "the f32 render failed"
  render "$s" -o "$work/$n.z.exr" --precision certified --certified-rerender none --certified-bound zero \
    --aov "$work/$n.z.aov.exr" || because "the faulted render failed"
  render "$s" -o "$work/$n.cr.exr" --precision certified --aov "$work/$n.cr.aov.exr" --stats-json "$work/$n.cr.json" \
    || because "the certified render with re-render failed"
  render "$s" -o "$work/$n.ccr.exr" --backend cpu --precision certified --aov "$work/$n.ccr.aov.exr" \
    --stats-json "$work/$n.ccr.json" || because "the CPU certified render with re-render failed"
  staging=()
  [[ $n == mesh ]] && staging=(--staging --tile 64)
  render "$s" -o "$work/$n.gr.exr" --precision certified --certified-rerender gpu --aov "$work/$n.gr.aov.exr" \
    --stats-json "$work/$n.gr.json" "${staging[@]}" || because "the certified render with the GPU's re-render failed"
  bands=()
  for k in 1 2 3 4; do bands+=(--band "$work/$n.ref.aov.band$k.exr"); done
  # A re-render leaves the certified pixels and the AOV's certified channel as the f32 pass
  # made them (checked below: the pixels re-rendered are the uncertified ones), so the
  # certificates are judged on the re-rendered frames: the GPU's f32 pass in .cr, the CPU
  # twin's in .ccr. --certified-rerender none runs in the faulted renders (.z).
  read -r _ _ plain _ < <(counts "$work/$n.f32.aov.exr" "$work/$n.ref.aov.exr")
  # The counts come from compares without the band (which leaves its pixels out of them),
  # the band's from compares with it.
  read -r unc bad rdec _ < <(counts "$work/$n.cr.aov.exr" "$work/$n.ref.aov.exr")
  read -r _ _ _ inband band < <(counts "$work/$n.cr.aov.exr" "$work/$n.ref.aov.exr" "${bands[@]}")
  read -r _ zbad _ _ < <(counts "$work/$n.z.aov.exr" "$work/$n.ref.aov.exr")
  read -r _ _ _ zband _ < <(counts "$work/$n.z.aov.exr" "$work/$n.ref.aov.exr" "${bands[@]}")
  read -r cunc cbad crdec _ < <(counts "$work/$n.ccr.aov.exr" "$work/$n.ref.aov.exr")
  [[ $bad == 0 ]] || because "GPU: $bad certified pixels decide otherwise than f64"
  [[ $inband == 0 ]] || because "${inband:-?} certified pixels lie in the band, where the reference itself flips"
  [[ $cbad == 0 ]] || because "CPU twin: $cbad certified pixels decide otherwise than f64"
  [[ $rdec == 0 ]] || because "re-rendered: $rdec pixels decide otherwise than f64"
  # Plain f32 differs from f64 here: the uncertified pixels must cover it. With the bound
  # zeroed the differences pass as certified, except where they come from a tie (an edge
  # function exactly 0: the cracks) or a kind without a bound (the cylinder).
  if [[ $plain != 0 ]]; then
    [[ $unc -gt 0 ]] || because "f32 differs on $plain pixels but none is uncertified"
  fi
  [[ $zbad == 0 && $zband == 0 ]] || faulted=$((faulted + 1))
  rer=$(json_num pixels_rerendered "$work/$n.cr.json")
  [[ $rer == "$unc" ]] || because "re-rendered $rer pixels, $unc have uncertified samples"
  [[ $crdec == 0 ]] || because "CPU re-rendered: $crdec pixels decide otherwise than f64"
  crer=$(json_num pixels_rerendered "$work/$n.ccr.json")
  [[ $crer == "$cunc" ]] || because "CPU: re-rendered $crer pixels, $cunc have uncertified samples"
  # Where each uncertified sample's first uncertified decision lies (cert_note): the three
  # counts add up to the uncertified samples, on the GPU and on its twin, and without a
  # reflected ray none lies on a bounce.
  for r in cr ccr; do
    j=$work/$n.$r.json
    at=$(($(json_num samples_uncertified_hit "$j") + $(json_num samples_uncertified_shadow "$j") +
      $(json_num samples_uncertified_bounce "$j")))
    [[ $at == "$(json_num samples_uncertified "$j")" ]] ||
      because "$r: hit, shadow and bounce add up to $at, not the $(json_num samples_uncertified "$j") uncertified"
    [[ $(json_num rays_reflection "$j") != 0 || $(json_num samples_uncertified_bounce "$j") == 0 ]] ||
      because "$r: $(json_num samples_uncertified_bounce "$j") uncertified on a bounce without reflected rays"
  done
  at="$(json_num samples_uncertified_hit "$work/$n.cr.json")/$(json_num samples_uncertified_shadow "$work/$n.cr.json")"
  at+="/$(json_num samples_uncertified_bounce "$work/$n.cr.json")"
  read -r grunc _ grdec _ < <(counts "$work/$n.gr.aov.exr" "$work/$n.ref.aov.exr")
  if [[ $grdec != 0 ]]; then
    # The GPU's f64 is another f64: where its own decisions differ from the reference's, the
    # pixels it re-renders may too, but nowhere else.
    render "$s" -o "$work/$n.g64.exr" --precision f64 --aov "$work/$n.g64.aov.exr" || because "the GPU f64 render failed"
    read -r _ _ g64dec _ < <(counts "$work/$n.g64.aov.exr" "$work/$n.ref.aov.exr")
    [[ $grdec -le $g64dec ]] ||
      because "GPU f64 re-rendered: $grdec pixels decide otherwise than f64, the GPU's own f64 render $g64dec"
  fi
  grer=$(json_num pixels_rerendered "$work/$n.gr.json")
  [[ $grer == "$grunc" ]] || because "GPU f64: re-rendered $grer pixels, $grunc have uncertified samples"
  # Each re-render traces the uncertified samples alone where the records name them all
  # (fewer than 32 samples a pixel: every scene here).
  for r in cr ccr gr; do
    [[ $(json_num samples_rerendered "$work/$n.$r.json") == $(json_num samples_uncertified "$work/$n.$r.json") ]] ||
      because "$r: re-rendered $(json_num samples_rerendered "$work/$n.$r.json") samples for $(json_num samples_uncertified "$work/$n.$r.json") uncertified"
  done
  # The default re-render is the f64 shader on a GPU, the CPU reference on a CPU device
  # (cmd_render.c, use_certified); a device without f64 fails the "gr" renders above.
  want=gpu
  [[ $(json_str device_type "$work/$n.cr.json") == cpu ]] && want=cpu
  [[ $(json_str rerender "$work/$n.gr.json") == gpu && $(json_str rerender "$work/$n.cr.json") == "$want" ]] ||
    because "re-rendered by $(json_str rerender "$work/$n.gr.json") (asked: gpu) and $(json_str rerender "$work/$n.cr.json") (the default on a $(json_str device_type "$work/$n.cr.json") device: $want)"
  echo "$n: f32 differs on $plain pixels; uncertified pixels GPU $unc, CPU $cunc (samples first at the hit/shadow/bounce $at); band $band; zero bound: $zbad broken, $zband in the band"
  check "$n" "$why"
done
# A pixel's re-render adds its uncertified samples, traced in f64, to the f32 sum of its
# certified ones (base/certified_marks.h). At 4 samples every uncertified sample is named
# in the record; at 36 those from 32 on cannot be, and their pixels are rendered whole.
# Either way the colours stay within f32's colour error of the f64 reference (a sample
# lost or counted twice moves a pixel by a quarter or a 36th of a sample's colour, far
# more than 1e-4), and the decisions are the reference's.
for spp in 4 36; do
  why=ok
  n=mesh_spp$spp
  common=(--width 120 --height 90 --spp $spp)
  render "$scenes/mesh.json" -o "$work/$n.ref.exr" --backend cpu --precision f64 --aov "$work/$n.ref.aov.exr" \
    "${common[@]}" || because "the f64 render failed"
  for r in cr ccr gr; do
    case $r in
      cr) args=(--certified-rerender cpu) ;;
      ccr) args=(--backend cpu) ;;
      gr) args=(--certified-rerender gpu --staging --tile 32) ;;
    esac
    render "$scenes/mesh.json" -o "$work/$n.$r.exr" --precision certified --aov "$work/$n.$r.aov.exr" \
      --stats-json "$work/$n.$r.json" "${common[@]}" "${args[@]}" || because "$r: the render failed"
    read -r _ _ dec _ < <(counts "$work/$n.$r.aov.exr" "$work/$n.ref.aov.exr")
    [[ $dec == 0 ]] || because "$r: $dec pixels decide otherwise than f64"
    "$bin" compare "$work/$n.$r.exr" "$work/$n.ref.exr" --json >"$work/cmp.json" 2>/dev/null
    err=$(json_num max_error "$work/cmp.json")
    awk -v e="$err" 'BEGIN { exit !(e != "" && e < 1e-4) }' || because "$r: a colour differs by $err from f64's"
    unc=$(json_num samples_uncertified "$work/$n.$r.json") sam=$(json_num samples_rerendered "$work/$n.$r.json")
    if [[ $spp == 4 ]]; then
      [[ $sam == "$unc" && $unc -gt 0 ]] || because "$r: re-rendered $sam samples for $unc uncertified"
    else
      # More than the uncertified ones: whole pixels where one from sample 32 on is.
      [[ $sam -gt $unc && $sam -le $(( $(json_num pixels_rerendered "$work/$n.$r.json") * spp )) ]] ||
        because "$r: re-rendered $sam samples for $unc uncertified, at most all of each pixel's"
    fi
    echo "$n $r: $unc samples uncertified, $sam re-rendered; colour within $err of f64"
  done
  check "$n: re-rendered samples" "$why"
done

# Mirror bounces: the AOV's first-sample channels record the primary hit's decisions, its
# digest (`decisions`) every bounce's. Three extremes scenes with every material a mirror
# (half, three bounces; plane and triangle mirrors, whose reflected rays carry the mirror
# planes' bound, docs/numerics.md §10), where plain f32 is 0.7-0.9 off f64 in some pixel: the
# certified frame, its uncertified samples re-rendered, makes the reference's decisions at
# every bounce and is within f32's colour error of f64 (1e-4); with the bound zeroed it is
# not, and pixels it calls certified decide otherwise at some bounce, so both comparisons
# can fail.
for n in S05_ground_h1e0 S11_huge_triangle_1e7 S20_axis_parallel; do
  why=ok
  python3 - "$extremes/$n.json" "$work/m_$n.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
for m in s.get("materials", {}).values():
    m["mirror"] = 0.5
s.setdefault("quality", {})["reflection_depth"] = 3
json.dump(s, open(sys.argv[2], "w"))
PY
  m=$work/m_$n
  render "$m.json" -o "$m.ref.exr" --backend cpu --precision f64 --aov "$m.ref.aov.exr" || because "the f64 render failed"
  render "$m.json" -o "$m.cr.exr" --precision certified --aov "$m.cr.aov.exr" || because "the certified render failed"
  render "$m.json" -o "$m.ccr.exr" --backend cpu --precision certified --aov "$m.ccr.aov.exr" ||
    because "the CPU certified render failed"
  render "$m.json" -o "$m.z.exr" --precision certified --certified-bound zero --aov "$m.z.aov.exr" ||
    because "the faulted render failed"
  for r in cr ccr z; do
    "$bin" compare "$m.$r.exr" "$m.ref.exr" --json >"$work/cmp.json" 2>/dev/null
    printf -v "err_$r" '%s' "$(json_num max_error "$work/cmp.json")"
    read -r _ mbad mdec _ < <(counts "$m.$r.aov.exr" "$m.ref.aov.exr")
    printf -v "dec_$r" '%s' "$mdec"
    printf -v "bad_$r" '%s' "$mbad"
  done
  [[ $dec_cr == 0 && $dec_ccr == 0 ]] || because "re-rendered: $dec_cr (GPU) and $dec_ccr (CPU) pixels decide otherwise than f64"
  [[ $bad_z -gt 0 ]] || because "with the bound zeroed no certified pixel decides otherwise at a bounce"
  awk -v e="$err_cr" 'BEGIN { exit !(e != "" && e < 1e-4) }' || because "GPU: a colour differs by $err_cr from f64's"
  awk -v e="$err_ccr" 'BEGIN { exit !(e != "" && e < 1e-4) }' || because "CPU twin: a colour differs by $err_ccr from f64's"
  awk -v e="$err_z" 'BEGIN { exit !(e != "" && e > 1e-2) }' || because "the zeroed bound left the colours within $err_z of f64's"
  echo "mirrored $n: certified within $err_cr of f64 (CPU twin $err_ccr), with the bound zeroed $err_z and $bad_z certified pixels deciding otherwise"
  check "mirrored $n" "$why"
done

expect_refusal "the cpu backend refuses the GPU's re-render" "$scenes/shadows.json" \
  "--certified-rerender gpu: the cpu backend has no GPU" --backend cpu --precision certified --certified-rerender gpu
why=ok
[[ $faulted -ge 10 ]] || because "the zeroed bound broke certificates on $faulted scenes only, expected 10 or more"
check "zero bound caught" "$why"
finish
