#!/usr/bin/env bash
# The speed/accuracy trade-off report (docs/accuracy.md): renders a fixed set of scenes
# under each variant of docs/accuracy.md (V0-V6) and each spp in {1, 4, 16, 64} on the GPU,
# measures the steady-state GPU time (median of --repeat frames) and the error against the
# CPU f64 reference (decision mismatches at the first sample, outside nothing; PSNR and max
# error against a 256-spp f64 render; acne and leaks where the scene defines them), and
# writes docs/accuracy.csv, a markdown table and a PNG plot (gnuplot) with the Pareto front.
#   tools/tradeoff.sh [OUTDIR]      (REPEAT=5 SIZE=160)
# On a cluster each (scene, variant, spp) point is a task of its own
# (tools/slurm/sweep.sh): TRADEOFF_POINT=I renders point I of 0..251 into the shared
# folder TRADEOFF_WORK; TRADEOFF_GATHER=1 then writes the CSV, table and plot from there;
# TRADEOFF_COUNT=1 prints the number of points.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/docs}
if [[ -n ${TRADEOFF_WORK:-} ]]; then
  work=$TRADEOFF_WORK
  mkdir -p "$work/rows"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  mkdir -p "$work/rows"
fi
bin=${VKRAYCAST:-$root/build/vkraycast}
[[ -x $bin ]] || { echo "build first (tools/demo.sh)" >&2; exit 2; }
repeat=${REPEAT:-5} size=${SIZE:-160}
ex=$root/tests/extremes/scenes
scenes=("$ex/S01_baseline.json" "$ex/S03_distance_1e3.json" "$ex/S07_closed_mesh_embree.json"
        "$ex/S13_translate_xyz_1e5.json" "$ex/S16_acne_X1e4_E10.json" "$ex/S17_contact_X1e2_h1e-3.json"
        "$ex/S21_many_spheres_D1e3.json" "$root/scenes/showcase.json" "$root/scenes/shadows.json")
# name | render options (V5 is the default; --precision pins what auto would choose)
variants=(
  "V0-fast|--sphere algebraic --triangle moller-trumbore --shadow-offset epsilon --camera-relative off --precision f32"
  "V1|--sphere geometric --triangle moller-trumbore --shadow-offset epsilon --camera-relative off --precision f32"
  "V2|--sphere geometric --triangle watertight --shadow-offset epsilon --camera-relative off --precision f32"
  "V3|--sphere geometric --triangle watertight --shadow-offset ulp --camera-relative off --precision f32"
  "V4|--sphere geometric --triangle watertight --shadow-offset error-bound --camera-relative off --precision f32"
  "V5-default|--precision f32"
  "V6-f64|--precision f64")
num() { sed -n "s/^[[:space:]]*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }
csv=$out/accuracy.csv
mkdir -p "$out/images" # the plot's folder: an OUTDIR outside docs/ starts empty
spps=(1 4 16 64)
points=$((${#scenes[@]} * ${#variants[@]} * ${#spps[@]}))
# One tile per frame (lavapipe's default, made explicit for other devices): every
# variant pays the same one dispatch per batch. 160x160 so that the shading, not
# lavapipe's ~8 ms fixed cost per dispatch, decides the times.
common=(--width "$size" --height "$size" --tile "$size" --quiet --allow-outside-paths)
# Point I (scene-major, then variant, then spp) into $work/rows/I.csv. Its references
# are rendered once into $work (tasks that race render the same file, renamed into place).
point() {
  local i=$1
  local s=${scenes[$((i / (${#variants[@]} * ${#spps[@]})))]}
  local v=${variants[$((i / ${#spps[@]} % ${#variants[@]}))]} spp=${spps[$((i % ${#spps[@]}))]}
  local n vn opts t
  n=$(basename "$s" .json)
  [[ -f $work/$n.ref256.exr ]] ||
    "$bin" render "$s" -o "$work/$n.ref256.exr" --backend cpu --precision f64 --spp 256 "${common[@]}" 2>/dev/null
  vn=${v%%|*} opts=${v#*|}
  t=$work/$n.$vn.$spp
  # The AOVs record each pixel's first sample, whose position depends on spp: the
  # decision reference renders the same samples.
  [[ -f $work/$n.ref$spp.aov.exr ]] || "$bin" render "$s" -o "$work/$n.ref$spp.exr" --aov "$work/$n.ref$spp.aov.exr" \
    --backend cpu --precision f64 --spp "$spp" "${common[@]}" 2>/dev/null
  # shellcheck disable=SC2086
  "$bin" render "$s" -o "$t.exr" --aov "$t.aov.exr" --spp "$spp" --repeat "$repeat" --stats-json "$t.json" \
    "${common[@]}" $opts 2>/dev/null
  "$bin" compare "$t.aov.exr" "$work/$n.ref$spp.aov.exr" --json >"$t.dec.json" || true
  "$bin" compare "$t.exr" "$work/$n.ref256.exr" --json >"$t.col.json" || true
  px=$((size * size)) hits=$(num a_hits "$t.dec.json") shadowed=$(num a_shadowed "$t.dec.json")
  mm=$(( $(num hit_mismatch "$t.dec.json") + $(num object_mismatch "$t.dec.json") + $(num shadow_mismatch "$t.dec.json") ))
  acne=0 leak=0
  case $n in
    S16_*) acne=$(awk -v a="$shadowed" -v h="$hits" 'BEGIN { printf "%.4g", h ? 100 * a / h : 0 }') ;;
    S07_*) leak=$(awk -v h="$hits" -v p="$px" 'BEGIN { printf "%.4g", 100 * (p - h) / p }') ;;
    S17_*) leak=$(awk -v a="$shadowed" -v h="$hits" 'BEGIN { printf "%.4g", h ? 100 * (h - a) / h : 0 }') ;;
  esac
  # compare writes 999 for the PSNR of identical images (MSE 0): the CSV says inf.
  psnr=$(num psnr "$t.col.json"); [[ $psnr == 999 ]] && psnr=inf
  printf '%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n' "$n" "$vn" "$spp" "$(num render_ms "$t.json")" \
    "$(awk -v m="$mm" -v p="$px" 'BEGIN { printf "%.4g", 100 * m / p }')" "$psnr" "$(num rms_error "$t.col.json")" \
    "$(num max_error "$t.col.json")" "$acne" "$leak" >"$work/rows/$i.csv"
}
if [[ ${TRADEOFF_COUNT:-0} == 1 ]]; then
  echo "$points"
  exit 0
fi
if [[ -n ${TRADEOFF_POINT:-} ]]; then
  ((TRADEOFF_POINT >= 0 && TRADEOFF_POINT < points)) || { echo "TRADEOFF_POINT: 0..$((points - 1))" >&2; exit 2; }
  point "$TRADEOFF_POINT"
  exit 0
fi
# PLOT_ONLY=1: the table and plot again from an existing accuracy.csv, rendering nothing;
# TRADEOFF_GATHER=1: from the rows the points left in TRADEOFF_WORK.
if [[ ${PLOT_ONLY:-0} != 1 ]]; then
  if [[ ${TRADEOFF_GATHER:-0} != 1 ]]; then
    for ((i = 0; i < points; i++)); do
      point "$i"
      if (((i + 1) % (${#variants[@]} * ${#spps[@]}) == 0)); then echo "  $((i + 1))/$points" >&2; fi
    done
  fi
  missing=()
  for ((i = 0; i < points; i++)); do [[ -s $work/rows/$i.csv ]] || missing+=("$i"); done
  ((${#missing[@]} == 0)) || { echo "tradeoff: points missing: ${missing[*]} (re-run them: --array=$(IFS=,; echo "${missing[*]}"))" >&2; exit 2; }
  echo "scene,variant,spp,gpu_ms,decision_mismatch_pct,psnr_db,rms_error,max_error,acne_pct,leak_pct" >"$csv"
  for ((i = 0; i < points; i++)); do cat "$work/rows/$i.csv"; done >>"$csv"
fi
command -v gnuplot >/dev/null || { echo "installing gnuplot-nox for the plot" >&2; apt-get install -y -qq gnuplot-nox >&2; }

# Per variant and spp: total GPU time over the scenes against the mean decision mismatch.
# PSNR over the scenes is that of their mean MSE (the mean of rms^2), not the mean of the
# per-scene PSNRs: a scene rendered identically (MSE 0, PSNR infinite) must count as no
# error, not as a 999 dB sentinel that swamps the others.
awk -F, 'NR > 1 { k = $2 "," $3; t[k] += $4; m[k] += $5; a[k] += $9; l[k] += $10; q[k] += $7 * $7; c[k]++ }
  END { for (k in t) printf "%s,%.2f,%.4f,%.2f,%.4f,%.4f\n", k, t[k], m[k] / c[k],
          (q[k] > 0 ? 10 * log(c[k] / q[k]) / log(10) : 999), a[k] / c[k], l[k] / c[k] }' \
  "$csv" | sort -t, -k3,3n -k1,1 >"$work/summary.csv"
# The Pareto front: no other point is both faster and more accurate.
awk -F, '{ t[NR] = $3; e[NR] = $4; line[NR] = $0 } END {
  for (i = 1; i <= NR; i++) { dominated = 0
    for (j = 1; j <= NR; j++) if (j != i && t[j] <= t[i] && e[j] <= e[i] && (t[j] < t[i] || e[j] < e[i])) dominated = 1
    print line[i] "," (dominated ? 0 : 1) } }' "$work/summary.csv" >"$work/pareto.csv"
{
  echo "| variant | spp | GPU ms (sum of ${#scenes[@]} scenes) | decision mismatch % (mean) | PSNR dB vs 256 spp (of the mean MSE) | acne % (S16) | leak % (S07, S17 mean) | Pareto |"
  echo "|---|---|---|---|---|---|---|---|"
  sort -t, -k2,2n -k1,1 "$work/pareto.csv" | awk -F, -v n="${#scenes[@]}" '{ printf "| %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6 * n, $7 * n / 2, ($8 ? "yes" : "") }'
} >"$work/table.md"
awk -F, '$8 == 1' "$work/pareto.csv" | sort -t, -k3,3n >"$work/front.csv"
# One line per variant through its spp points (1, 4, 16, 64 from left to right), both axes
# log, a colour each; the Pareto front as rings. A mean of 0 mismatches (f64) sits on the
# floor line, as log axes have no 0.
floor=0.001
colors=("#d62728" "#ff7f0e" "#bcbd22" "#8c564b" "#9467bd" "#1f77b4" "#2ca02c")
plots=()
i=0
for v in "${variants[@]}"; do
  vn=${v%%|*}
  awk -F, -v v="$vn" -v f="$floor" '$1 == v { print $2 "," $3 "," ($4 > f ? $4 : f) }' "$work/pareto.csv" |
    sort -t, -k1,1n >"$work/line.$vn.csv"
  plots+=("\"$work/line.$vn.csv\" using 2:3 with linespoints lw 2 pt 7 ps 1 lc rgb \"${colors[$i]}\" title \"$vn\"")
  i=$((i + 1))
done
plots+=("\"$work/front.csv\" using 3:(\$4 > $floor ? \$4 : $floor) with points pt 6 ps 3 lw 2 lc rgb \"black\" title \"Pareto front\"")
gnuplot <<GP
set terminal pngcairo size 960,600 font "sans,11"
set output "$out/images/tradeoff.png"
set datafile separator ","
set logscale xy
set format y "%g"
set xlabel "GPU time, ms (sum over the ${#scenes[@]} scenes, lavapipe, ${size}x${size}); each line: 1, 4, 16, 64 spp"
set ylabel "decision mismatches vs CPU f64, % of pixels (mean; 0 drawn at $floor)"
set key outside right top
set grid
plot $(IFS=,; echo "${plots[*]}")
GP
cat "$work/table.md"
echo "wrote $csv, the table (above), $out/images/tradeoff.png" >&2
