#!/usr/bin/env bash
# Parsing scales linearly (issue 13): each kind of named thing at N, 2N and 4N, the median
# over ROUNDS processes of parse_ms from --stats-json (reading plus parsing the scene),
# and the ratio to the previous size: about 2 when linear, 4 when quadratic.
# Usage: tools/bench_parse.sh [BIN]   Env: N (50000), ROUNDS (3)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/vkraycast} n=${N:-50000} rounds=${ROUNDS:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
echo "$bin; $(nproc) cores; median of $rounds processes; parse_ms = read + parse"
echo
echo "| kind | count | file MiB | parse ms | ratio to half the count |"
echo "|---|---|---|---|---|"
for kind in json-materials test-materials test-vertices; do
  prev=
  for k in 1 2 4; do
    count=$((n * k)) ext=json
    [[ $kind == test-* ]] && ext=test
    tests/reliability/gen_scale.sh "$kind" "$count" "$work/s.$ext"
    for ((r = 0; r < rounds; r++)); do
      "$bin" render "$work/s.$ext" -o "$work/o.png" --backend cpu --quiet --width 1 --height 1 \
        --stats-json "$work/st.json"
      sed -n 's/.*"parse_ms":[[:space:]]*\([0-9.e+]*\).*/\1/p' "$work/st.json"
    done | median >"$work/ms"
    ms=$(cat "$work/ms")
    mib=$(awk -v b="$(stat -c %s "$work/s.$ext")" 'BEGIN {printf "%.1f", b / 1048576}')
    ratio=-
    [[ -n $prev ]] && ratio=$(awk -v a="$ms" -v b="$prev" 'BEGIN {printf "%.2f", a / b}')
    printf '| %s | %d | %s | %.0f | %s |\n' "$kind" "$count" "$mib" "$ms" "$ratio"
    prev=$ms
  done
done
