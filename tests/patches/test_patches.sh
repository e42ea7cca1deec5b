#!/usr/bin/env bash
# Bezier patches (docs/scene-format.md, "Bezier patches"), closed forms on both backends
# and in both precisions:
# - a flat patch over a square shows the same pixels as the square's two triangles;
# - the hyperbolic paraboloid z = x y, a bilinear patch (given as 16 bicubic points in
#   JSON, and as a degree 1 x 1 patch in a patch file, which the loader raises): every hit
#   pixel's normal (-y, -x, 1) and depth agree, x y from the normal equals the depth's, and
#   x and y lie in the pixel; the two forms give the same pixels;
# - the teapot's lid seen from straight above: the apex, where a row of the net collapses
#   to a point (dS/du = 0), has the normal straight up, and no pixel has a NaN;
# - a teapot far away for its size: the precision budget asks for f64, auto renders it,
#   and f64 matches the CPU reference where forced f32 does not;
# - a prepared scene (vkraycast prepare) renders the same pixels as the scene.
# Usage: test_patches.sh VKRAYCAST WORKDIR
set -uo pipefail
bin=$1 work=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
command -v oiiotool >/dev/null || { echo "FAIL: oiiotool (openimageio-tools) is missing"; exit 1; }

variants=("--backend gpu --precision f32" "--backend gpu --precision f64" "--backend cpu --precision f64"
  "--backend cpu --precision f32")
# Under the sanitizers (tools/test.sh's second pass) one variant: the same host code runs
# for every one; the numbers are the first pass's.
[[ -z ${ASAN_OPTIONS:-} ]] || variants=("--backend gpu --precision f32")
num() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2"; }

# 1. A flat patch against two triangles: the square [-1.5, 1.5]^2 at z = 0, seen
# obliquely, lit from the side; its net is the square's points at thirds (exact in f32).
net=""
for r in 0 1 2 3; do for c in 0 1 2 3; do
  net+="[$(awk -v c=$c -v r=$r 'BEGIN { printf "%g, %g, 0", c - 1.5, r - 1.5 }')]"
  [[ $r$c == 33 ]] || net+=", "
done; done
flat() { # FILE OBJECTS
  cat >"$1" <<EOF
{ "image": { "width": 48, "height": 40, "samples_per_pixel": 1 },
  "camera": { "eye": [1, -3, 6], "look_at": [0, 0, 0], "fov_y_deg": 40 },
  "materials": { "m": { "ambient": [0.1, 0.1, 0.1], "diffuse": [0.7, 0.6, 0.5], "specular": [0.4, 0.4, 0.4], "shininess": 20 } },
  "lights": [ { "type": "point", "position": [-3, 2, 4], "intensity": [30, 30, 30] } ],
  "objects": [ $2 ] }
EOF
}
flat "$work/flat_patch.json" "{ \"type\": \"bezier_patch\", \"control_points\": [$net], \"material\": \"m\" }"
flat "$work/flat_triangles.json" "{ \"type\": \"triangle\", \"vertices\": [[-1.5, -1.5, 0], [1.5, -1.5, 0], [1.5, 1.5, 0]], \"material\": \"m\" },
    { \"type\": \"triangle\", \"vertices\": [[-1.5, -1.5, 0], [1.5, 1.5, 0], [-1.5, 1.5, 0]], \"material\": \"m\" }"
for v in "${variants[@]}"; do
  why=ok
  # shellcheck disable=SC2086
  "$bin" render "$work/flat_patch.json" $v --quiet -o "$work/fp.exr" --stats-json "$work/fp.json" ||
    because "the patch render failed"
  # shellcheck disable=SC2086
  "$bin" render "$work/flat_triangles.json" $v --quiet -o "$work/ft.exr" || because "the triangles' render failed"
  # The same surface through different arithmetic: colours within 1e-5, no pixel apart.
  "$bin" compare "$work/fp.exr" "$work/ft.exr" --fail 1e-5 --hardfail 1e-5 >"$work/cmp" 2>&1 ||
    because "not the triangles' pixels: $(grep -m1 'max error' "$work/cmp")"
  [[ "$(num patch_unconverged "$work/fp.json")" == 0 ]] || because "unconverged rays on a flat patch"
  check "flat patch = its two triangles, $v" "$why"
done

# 2. z = x y over [-1.5, 1.5]^2: x = 3u - 1.5, y = 3v - 1.5, a bilinear patch whose
# raised net is its values at the thirds (exact in f32). Parallel camera from +z.
net=""
for r in 0 1 2 3; do for c in 0 1 2 3; do
  net+="[$(awk -v c=$c -v r=$r 'BEGIN { x = c - 1.5; y = r - 1.5; printf "%g, %g, %g", x, y, x * y }')]"
  [[ $r$c == 33 ]] || net+=", "
done; done
printf '1\n1 1\n-1.5 -1.5 2.25\n1.5 -1.5 -2.25\n-1.5 1.5 -2.25\n1.5 1.5 2.25\n' >"$work/saddle.bpt"
saddle() { # FILE OBJECT
  cat >"$1" <<EOF
{ "image": { "width": 32, "height": 32, "samples_per_pixel": 1 },
  "camera": { "projection": "parallel", "eye": [0, 0, 10], "look_at": [0, 0, 0], "up": [0, 1, 0], "view_height": 3.2 },
  "materials": { "m": { "ambient": [0.2, 0.2, 0.2], "diffuse": [0.8, 0.8, 0.8] } },
  "lights": [ { "type": "directional", "direction": [0.3, -0.2, -1], "intensity": [1, 1, 1] } ],
  "objects": [ $2 ] }
EOF
}
saddle "$work/saddle.json" "{ \"type\": \"bezier_patch\", \"control_points\": [$net], \"material\": \"m\" }"
saddle "$work/saddle_file.json" "{ \"type\": \"bezier_patches\", \"file\": \"saddle.bpt\", \"material\": \"m\" }"
for v in "${variants[@]}"; do
  why=ok
  # shellcheck disable=SC2086
  "$bin" render "$work/saddle.json" $v --quiet -o "$work/s.exr" --aov "$work/s.aov.exr" || because "the render failed"
  # shellcheck disable=SC2086
  "$bin" render "$work/saddle_file.json" $v --quiet -o "$work/sf.exr" || because "the patch file's render failed"
  "$bin" compare "$work/s.exr" "$work/sf.exr" --fail 0 --hardfail 0 >"$work/cmp" 2>&1 ||
    because "the patch file's bilinear patch, raised, is not the JSON net: $(grep -m1 'max error' "$work/cmp")"
  # The AOVs hold f32 (t near 10: ulps of 1e-6) whatever the precision; f32's own
  # arithmetic adds its Newton tolerance.
  tol=2e-5
  [[ $v == *f64* ]] && tol=2e-6
  # Pixel (i, j): x in [-1.6 + 0.1 i, -1.6 + 0.1 (i + 1)], y in [1.6 - 0.1 (j + 1), 1.6 - 0.1 j].
  # The channels as read back: R G B decisions hit object shadow t uncertified N.X N.Y N.Z.
  report=$(oiiotool --dumpdata "$work/s.aov.exr" 2>/dev/null | awk -v tol=$tol '
    /Pixel \(/ { gsub(/[(),:]/, " "); i = $2; j = $3; hit = $8; t = $11; nx = $13; ny = $14; nz = $15
      if (hit != 1) { miss++; next }
      hits++
      x = -ny / nz; y = -nx / nz
      d = x * y - (10 - t); if (d < 0) d = -d; if (d > worst) worst = d
      e = (nx * nx + ny * ny + nz * nz) - 1; if (e < 0) e = -e; if (e > 1e-5) bad = bad " unit(" i "," j ")"
      if (x < -1.6 + 0.1 * i - tol || x > -1.6 + 0.1 * (i + 1) + tol || y < 1.6 - 0.1 * (j + 1) - tol || y > 1.6 - 0.1 * j + tol)
        bad = bad " place(" i "," j ")"
    }
    END { printf "%d %d %.3g %s\n", hits, miss, worst, substr((worst > tol ? "depth" : "") bad, 1, 200) }')
  read -r hits misses worst problems <<<"$report"
  # 30 x 30 pixels lie inside the square; the frame's border ring of 124 misses it.
  [[ $hits == 900 && $misses == 124 ]] || because "$hits hits and $misses misses, expected 900 and 124"
  [[ -z ${problems:-} ]] || because "normal against depth off by $worst (at most $tol), or: $problems"
  check "z = x y: normals (-y, -x, 1) and depths exact (worst $worst), $v" "$why"
done

# 3. The teapot's lid from straight above (the scene's y is up): the apex's normal.
cat >"$work/lid.json" <<EOF
{ "image": { "width": 33, "height": 33, "samples_per_pixel": 1 },
  "camera": { "projection": "parallel", "eye": [0, 10, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "view_height": 0.2 },
  "materials": { "m": { "ambient": [0.2, 0.2, 0.2], "diffuse": [0.8, 0.8, 0.8] } },
  "lights": [ { "type": "directional", "direction": [0, -1, 0], "intensity": [1, 1, 1] } ],
  "objects": [ { "type": "bezier_patches", "file": "$root/scenes/patches/teapot.bpt", "material": "m",
                 "transform": { "rotate_deg": [-90, 0, 0] } } ] }
EOF
for v in "${variants[@]}"; do
  why=ok
  # shellcheck disable=SC2086
  "$bin" render "$work/lid.json" $v --quiet --allow-outside-paths -o "$work/l.exr" --aov "$work/l.aov.exr" ||
    because "the render failed"
  oiiotool --dumpdata "$work/l.aov.exr" 2>/dev/null | grep -qi nan && because "a NaN in the AOVs"
  centre=$(oiiotool --dumpdata "$work/l.aov.exr" 2>/dev/null | sed -n 's/^ *Pixel (16, 16): *//p')
  read -r _ _ _ _ hit _ _ t _ nx ny nz <<<"$centre"
  awk -v h="$hit" -v t="$t" -v x="$nx" -v y="$ny" -v z="$nz" 'BEGIN {
    exit !(h == 1 && y > 0.9999 && x * x + z * z < 1e-4 && t > 6.84 && t < 6.86) }' ||
    because "the apex pixel: hit $hit, t $t (10 - 3.15), normal ($nx, $ny, $nz), not straight up"
  check "teapot lid apex: the limit normal is straight up, no NaN, $v" "$why"
done

# 4. Far away: the teapot at a thousandth of its size, 40 units off (its pieces 2.8e5 of
# their size away). The precision budget asks for f64, naming a patch piece, and
# --precision auto renders in f64 where the device has it; f64 on the GPU then matches the
# CPU reference in f64, and forced f32 makes more first-sample decisions apart from it
# (acne and holes on the body: that is what the budget saw).
cat >"$work/far.json" <<EOF
{ "image": { "width": 64, "height": 48 },
  "camera": { "eye": [0, 0.005, 40], "look_at": [0, 0.0015, 0], "fov_y_deg": 0.01 },
  "materials": { "m": { "diffuse": [0.8, 0.8, 0.8] } },
  "lights": [ { "type": "directional", "direction": [0.3, -1, -0.5], "intensity": [1, 1, 1] } ],
  "objects": [ { "type": "bezier_patches", "file": "$root/scenes/patches/teapot.bpt", "material": "m",
                 "transform": { "rotate_deg": [-90, 0, 0], "scale": [0.001, 0.001, 0.001] } } ] }
EOF
why=ok
far=("$work/far.json" --allow-outside-paths --quiet)
"$bin" render "${far[@]}" -o "$work/far_auto.exr" --aov "$work/far_auto.aov.exr" --stats-json "$work/far.stats" \
  2>"$work/far.err" || because "the auto render failed"
[[ $(json_str precision "$work/far.stats") == f64 ]] || because "auto rendered in $(json_str precision "$work/far.stats")"
(( $(json_num budget_needs_f64 "$work/far.stats") > 0 )) || because "the budget found nothing"
grep -q "first patch piece" "$work/far.err" || because "the warning names no patch piece: $(head -c 300 "$work/far.err")"
if [[ -z ${ASAN_OPTIONS:-} ]]; then
  "$bin" render "${far[@]}" --backend cpu -o "$work/far_ref.exr" --aov "$work/far_ref.aov.exr" 2>/dev/null ||
    because "the CPU f64 render failed"
  "$bin" render "${far[@]}" --precision f32 -o "$work/far32.exr" --aov "$work/far32.aov.exr" 2>/dev/null ||
    because "the f32 render failed"
  "$bin" compare "$work/far_auto.aov.exr" "$work/far_ref.aov.exr" --preset same-precision >"$work/cmp" 2>&1 ||
    because "GPU f64 against CPU f64: $(grep -m1 FAIL "$work/cmp")"
  "$bin" compare "$work/far_auto.aov.exr" "$work/far_ref.aov.exr" --json >"$work/c64.json" 2>/dev/null
  "$bin" compare "$work/far32.aov.exr" "$work/far_ref.aov.exr" --json >"$work/c32.json" 2>/dev/null
  d64=$(( $(json_num hit_mismatch "$work/c64.json") + $(json_num shadow_mismatch "$work/c64.json") ))
  d32=$(( $(json_num hit_mismatch "$work/c32.json") + $(json_num shadow_mismatch "$work/c32.json") ))
  (( d32 > d64 )) || because "f32 makes $d32 hit and shadow decisions apart from the f64 reference, f64 $d64"
fi
check "a far teapot: the budget asks f64 and auto renders it (f32 apart in ${d32:-?} decisions, f64 in ${d64:-?})" "$why"

# 5. A prepared scene's pixels are the scene's.
why=ok
"$bin" prepare "$work/saddle.json" -o "$work/saddle.vkrs" --quiet || because "prepare failed"
"$bin" render "$work/saddle.vkrs" --quiet -o "$work/sp.exr" || because "rendering the prepared scene failed"
"$bin" render "$work/saddle.json" --quiet -o "$work/sd.exr" || because "rendering the scene failed"
"$bin" compare "$work/sp.exr" "$work/sd.exr" --fail 0 --hardfail 0 >"$work/cmp" 2>&1 ||
  because "not the same pixels: $(grep -m1 'max error' "$work/cmp")"
check "a prepared patch scene renders the scene's pixels" "$why"
finish
