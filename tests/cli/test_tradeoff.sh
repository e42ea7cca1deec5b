#!/usr/bin/env bash
# `vkraycast tradeoff` on a user's scene, as a user runs it: from a folder of their own
# with a relative scene path, writing only into --out. Checks the rows (one per scene x
# variant x spp, every one measured), real values (f64 and certified mode against the f64
# reference make the same decisions; colour error shrinks as spp grows), the summary, the plot's legend
# and spp labels, a variant of the user's own, a job array's --point/--gather, and bad
# usage. Usage: test_tradeoff.sh VKRAYCAST SCENES_DIR
set -uo pipefail
bin=$1 scenes=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=../check.sh
source "$(dirname "$0")/../check.sh"

mkdir -p "$work/user" "$work/user/my"
cp "$scenes/shadows.json" "$work/user/my/scene.json"
cd "$work/user" || exit 2
small=(--width 40 --height 30 --spp-list 1,4 --reference-spp 16 --repeat 2)

why=ok
"$bin" tradeoff my/scene.json --out results --variants fast,default,certified,f64 "${small[@]}" >table.md 2>progress.txt ||
  because "exit status $?: $(tail -3 progress.txt)"
[[ -s results/tradeoff.csv && -s results/tradeoff-summary.csv && -s results/tradeoff.svg ]] || because "outputs missing"
# Nothing outside --out: the caller's folder holds what it held plus results/ and the
# redirections.
[[ "$(ls | sort | tr '\n' ' ')" == "my progress.txt results table.md " ]] || because "wrote elsewhere: $(ls)"
[[ "$(ls my)" == scene.json ]] || because "wrote beside the scene: $(ls my)"
check "runs from the user's folder, writes only into --out" "$why"

why=ok
rows=$(tail -n +2 results/tradeoff.csv | wc -l)
[[ $rows == 8 ]] || because "$rows rows, expected 8 (1 scene x 4 variants x 2 spp)"
bad=$(tail -n +2 results/tradeoff.csv | awk -F, '$16 != "ok"' | head -3)
[[ -z $bad ]] || because "points not measured: $bad"
# The columns: precision as the variant asked, times positive.
awk -F, 'NR > 1 && (($2 == "f64") != ($4 == "f64") || !($5 > 0) || !($7 > 0) || !($8 > 0)) { exit 1 }' results/tradeoff.csv ||
  because "precision or times wrong: $(cat results/tradeoff.csv)"
check "one measured row per point" "$why"

why=ok
# f64 renders the reference's arithmetic, and certified mode re-renders in it whatever it
# cannot certify: no decision differs.
for v in f64 certified; do
  d=$(awk -F, -v v=$v '$2 == v { s += $9 } END { print s + 0 }' results/tradeoff.csv)
  [[ $d == 0 ]] || because "$v decisions differ on $d % of pixels"
done
# More samples, nearer the many-sample reference: PSNR grows from 1 to 4 spp.
awk -F, '$2 == "default" { p[$3] = $13 } END { exit !(p[4] > p[1] + 3) }' results/tradeoff.csv ||
  because "PSNR does not grow with spp: $(grep default results/tradeoff.csv)"
check "values: f64 and certified exact in decisions, colour converges with spp" "$why"

why=ok
grep -q '^| fast | 1 |' table.md || because "no table row for fast at 1 spp"
[[ $(grep -c ',yes,' results/tradeoff-summary.csv) -ge 1 ]] || because "no Pareto point"
for v in fast default certified f64; do
  grep -q ">$v</text>" results/tradeoff.svg || because "legend lacks $v"
done
grep -q 'Moller-Trumbore' results/tradeoff.svg || because "legend does not say what fast is"
[[ $(grep -c '<polyline' results/tradeoff.svg) == 4 ]] || because "not one line per variant"
grep -q ">4</text>" results/tradeoff.svg || because "spp not marked on the points"
grep -q '\[8/8\]' progress.txt || because "no progress: $(head -2 progress.txt)"
check "table, summary and a plot that says what each line is" "$why"

why=ok
"$bin" tradeoff my/scene.json --out custom --variant 'nobvh: --accel none' --variant 'bvh: --accel bvh' \
  --width 40 --height 30 --spp-list 1 --reference-spp 4 --repeat 2 -q >/dev/null 2>err.txt ||
  because "custom variants: exit $?: $(cat err.txt)"
[[ $(tail -n +2 custom/tradeoff.csv | cut -d, -f2 | tr '\n' ' ') == "nobvh bvh " ]] || because "$(cat custom/tradeoff.csv)"
# Brute force and the BVH make the same decisions (the BVH's tie rule), so the same error.
[[ $(tail -n +2 custom/tradeoff.csv | cut -d, -f9,13 | sort -u | wc -l) == 1 ]] ||
  because "brute force and BVH differ: $(cat custom/tradeoff.csv)"
check "variants of the user's own" "$why"

why=ok
n=$("$bin" tradeoff my/scene.json --out farm --variants default,f64 --points "${small[@]}")
[[ $n == 4 ]] || because "--points said $n, expected 4"
for ((i = n - 1; i >= 0; i--)); do
  "$bin" tradeoff my/scene.json --out farm --variants default,f64 --point "$i" "${small[@]}" -q 2>>err.txt ||
    because "--point $i: exit $?"
done
"$bin" tradeoff my/scene.json --out farm --variants default,f64 --gather "${small[@]}" -q >/dev/null 2>>err.txt ||
  because "--gather: exit $?: $(cat err.txt)"
[[ $(cut -d, -f1-4,9-12 farm/tradeoff.csv) == $(grep -vE ',(fast|certified),' results/tradeoff.csv | cut -d, -f1-4,9-12) ]] ||
  because "points gathered differ from one run's: $(cat farm/tradeoff.csv)"
rm farm/points/2.csv
"$bin" tradeoff my/scene.json --out farm --variants default,f64 --gather "${small[@]}" -q >/dev/null 2>err.txt
st=$?
[[ $st == 2 ]] && grep -q "point 2 is missing" err.txt || because "a missing point: exit $st, $(cat err.txt)"
check "a job array's points gathered" "$why"

expect_exit2 "bad --spp-list" results/x "--spp-list: expected" "$bin" tradeoff my/scene.json --out r2 --spp-list 1,0
expect_exit2 "unknown variant" results/x "no variant 'defualt' (did you mean default?)" \
  "$bin" tradeoff my/scene.json --out r2 --variants defualt
expect_exit2 "no --out" results/x "no output folder given" "$bin" tradeoff my/scene.json
expect_exit2 "missing scene" results/x "nothere.json" "$bin" tradeoff nothere.json --out r2
finish
