#!/usr/bin/env bash
# Light passes (docs/performance.md, "Light passes"): the showcase with LIGHTS seeded point
# lights, too many for one dispatch on lavapipe, rendered by the GPU path in light passes
# and by the CPU reference in f32 and f64. ROUNDS rounds, the three backends in turn in each
# round; each figure is the median over the rounds: render_ms, the process's wall and CPU
# seconds, and the GPU's dispatches and lights per pass.
#   tools/bench_light_passes.sh      (ROUNDS=3 LIGHTS=5000 SIZE=160x100)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$root/build/vkraycast
[[ -x $bin ]] || { echo "build first (tools/demo.sh)" >&2; exit 2; }
rounds=${ROUNDS:-3} lights=${LIGHTS:-5000} size=${SIZE:-160x100}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
num() { sed -n "s/^[[:space:]]*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
python3 - "$root/scenes/showcase.json" "$lights" "${size%x*}" "${size#*x}" "$work/scene.json" <<'PY'
import json, random, sys
src, n, w, h, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
s = json.load(open(src))
r = random.Random(5)
s["image"] = {"width": w, "height": h, "samples_per_pixel": 1}
# The showcase's light, spread: 60 units of intensity over the lights.
s["lights"] = [{"type": "point", "position": [r.uniform(-6, 6), r.uniform(1, 8), r.uniform(-4, 7)],
                "intensity": [60.0 / n] * 3} for _ in range(n)]
json.dump(s, open(out, "w"))
PY
backends=("GPU f32, light passes|--backend gpu" "CPU reference f32|--backend cpu --precision f32"
          "CPU reference f64|--backend cpu")
for ((r = 0; r < rounds; r++)); do
  for i in "${!backends[@]}"; do
    args=${backends[$i]#*|}
    # shellcheck disable=SC2086
    /usr/bin/time -f "%e %U %S" -o "$work/time" "$bin" render "$work/scene.json" -o "$work/o.png" $args --quiet \
      --stats-json "$work/s.json"
    read -r wall user sys <"$work/time"
    echo "$(num render_ms "$work/s.json") $wall $(awk -v u="$user" -v s="$sys" "BEGIN { print u + s }")" >>"$work/b$i.txt"
    echo "$(num dispatches "$work/s.json") $(num lights_per_pass "$work/s.json")" >"$work/d$i.txt"
  done
done
echo "| backend | render_ms | wall s | CPU s | dispatches | lights per pass |"
echo "|---|---|---|---|---|---|"
for i in "${!backends[@]}"; do
  read -r d p <"$work/d$i.txt"
  printf '| %s | %.0f | %.2f | %.1f | %s | %s |\n' "${backends[$i]%%|*}" \
    "$(cut -d' ' -f1 "$work/b$i.txt" | median)" "$(cut -d' ' -f2 "$work/b$i.txt" | median)" \
    "$(cut -d' ' -f3 "$work/b$i.txt" | median)" "${d:-–}" "${p:-–}"
done
