#!/usr/bin/env bash
# Benchmark of the scene-buffer kinds (image, texel, storage): a thin user of
# `vkraycast tradeoff`, whose variants here are the three kinds. ROUNDS rounds, each one
# tradeoff run over every scene and kind (kinds interleaved per scene, each render its
# own process with --repeat FRAMES); reports the median over rounds of each render's
# steady-state time (GPU timestamps, the median of frames 2..FRAMES), the wall time per
# frame, process CPU time and Mrays/s (primary + shadow + reflection).
# Usage: tools/bench.sh [SCENE...]   (default: scenes/*.json and 4/16-sphere grids)
# Env: ROUNDS (3), FRAMES (6), SIZE ("--width 320 --height 200"), SPP (1).
set -euo pipefail
cd "$(dirname "$0")/.."
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
rounds=${ROUNDS:-3} frames=${FRAMES:-6} size=${SIZE---width 320 --height 200} spp=${SPP-1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenes=("$@")
if ((${#scenes[@]} == 0)); then
  for n in 4 16; do tools/gen_sphere_grid.sh $n >"$work/grid$n.json"; done
  scenes=(scenes/*.json "$work/grid4.json" "$work/grid16.json")
fi
for ((r = 0; r < rounds; r++)); do
  build/vkraycast tradeoff "${scenes[@]}" --out "$work/round$r" --spp-list "${spp:-scene}" --repeat "$frames" \
    --reference-spp 1 --quiet --render-args="$size --allow-outside-paths" \
    --variant 'image: --scene-buffers image' --variant 'texel: --scene-buffers texel' \
    --variant 'storage: --scene-buffers storage' >/dev/null
done
echo "device: $(build/vkraycast devices | sed -n 2p | cut -c7-46 | sed 's/ *$//'), $(nproc) cores; ${size:-scene size} ${spp:+--spp $spp}; $rounds rounds x --repeat $frames"
echo
echo "| scene | buffers | render ms (GPU) | wall ms/frame | CPU ms (process) | Mrays/s |"
echo "|---|---|---|---|---|---|"
# Median over the rounds of each (scene, kind): columns render_ms, wall_ms, cpu_ms, mrays_per_s.
cat "$work"/round*/tradeoff.csv | awk -F, '$1 != "scene" && $NF == "ok" { k = $1 "," $2; n[k]++
    for (c = 5; c <= 8; c++) v[k, c, n[k]] = $c; order[k] = ++seen[k] == 1 ? ++keys : order[k]; name[order[k]] = k }
  function median(k, c,    i, j, t, a, m) { m = n[k]; for (i = 1; i <= m; i++) a[i] = v[k, c, i]
    for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
    return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2 }
  END { for (i = 1; i <= keys; i++) { k = name[i]; split(k, p, ",")
    printf "| %s | %s | %.1f | %.1f | %.0f | %.2f |\n", p[1], p[2], median(k, 5), median(k, 6), median(k, 7), median(k, 8) } }'
