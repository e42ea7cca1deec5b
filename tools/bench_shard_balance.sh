#!/usr/bin/env bash
# Shard balance on a scene whose cost sits in a few rows (docs/cluster.md, "Finer work
# units"): a strip of 200 small mirror spheres lit by 64 lights, 4 rows tall in a 640 x 400
# frame at 16 spp; the rest is sky. Renders it as N shards (default 8) with each binary
# given, one shard after another on this machine, each REPEAT times (default 3), and
# prints every shard's region and its median render_ms (--stats-json: the dispatches or
# the reference's rows, without the fixed cost), then the slowest shard against the mean:
# the farm's makespan is its slowest shard. Beside it, each shard process's CPU time
# (cpu_ms: the whole process, fixed costs included).
# Usage: tools/bench_shard_balance.sh BASELINE_VKRAYCAST NEW_VKRAYCAST [N] [REPEAT] [render args...]
set -euo pipefail
old=$1 new=$2 n=${3:-8} repeat=${4:-3}
shift $(($# < 4 ? $# : 4))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$work/strip.json" <<'PY'
import json, sys
spheres = [{"type": "sphere", "center": [-6 + 12 * i / 199, 0, 0], "radius": 0.03, "material": "chrome"}
           for i in range(200)]
lights = [{"type": "point", "position": [-6 + 12 * k / 63, 3, 4], "intensity": [0.4, 0.4, 0.4]} for k in range(64)]
scene = {"version": 1, "image": {"width": 640, "height": 400, "samples_per_pixel": 16},
         "camera": {"projection": "perspective", "eye": [0, 0, 8], "look_at": [0, 0, 0], "up": [0, 1, 0],
                    "fov_y_deg": 40},
         "background": [0.05, 0.07, 0.12], "ambient_light": [1, 1, 1],
         "materials": {"chrome": {"ambient": [0.01, 0.01, 0.01], "diffuse": [0.3, 0.3, 0.3],
                                  "specular": [0.9, 0.9, 0.9], "shininess": 200, "mirror": [0.8, 0.8, 0.85]}},
         "lights": lights, "objects": spheres}
json.dump(scene, open(sys.argv[1], "w"), indent=1)
PY
for bin in "$old" "$new"; do
  echo "== $bin, $n shards, median of $repeat runs each"
  times=()
  for ((i = 0; i < n; i++)); do
    runs=() cpus=()
    for ((r = 0; r < repeat; r++)); do
      "$bin" render "$work/strip.json" --shard "$i/$n" -o "$work/s.exr" --stats-json "$work/s.json" --quiet "$@"
      read -r ms cpu < <(python3 -c 'import json,sys; d = json.load(open(sys.argv[1])); print(d["render_ms"], d["cpu_ms"])' "$work/s.json")
      runs+=("$ms") cpus+=("$cpu")
    done
    median=$(printf '%s\n' "${runs[@]}" | sort -g | sed -n "$(((repeat + 1) / 2))p")
    cpu=$(printf '%s\n' "${cpus[@]}" | sort -g | sed -n "$(((repeat + 1) / 2))p")
    region=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["region"])' "$work/s.json")
    printf 'shard %d/%d  region %-22s render_ms %7.1f  process cpu_ms %7.1f\n' "$i" "$n" "$region" "$median" "$cpu"
    times+=("$median")
  done
  printf '%s\n' "${times[@]}" | awk '{s += $1; if ($1 > m) m = $1} END {printf "slowest %.1f ms, mean %.1f ms, slowest / mean %.2f, sum %.0f ms\n", m, s / NR, m / (s / NR), s}'
done
