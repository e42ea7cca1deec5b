#!/usr/bin/env bash
# The trade-off study of docs/accuracy.md: `vkraycast tradeoff` on the scenes that page
# measures (extremes S01, S03, S07, S13, S16, S17, S21 and the showcase and shadows
# examples), 160x160, spp 1, 4, 16 and 64, one tile per frame. A thin user of the
# command: anyone can run the same on their own scenes (README, "Speed against accuracy").
#   tools/tradeoff.sh OUTDIR [more tradeoff options, e.g. --point I, --gather, --points]
# Writes OUTDIR/tradeoff.csv, tradeoff-summary.csv, tradeoff.svg and nothing else; to
# update the docs, copy OUTDIR/tradeoff.csv to docs/accuracy.csv and OUTDIR/tradeoff.svg
# to docs/images/tradeoff.svg.
set -euo pipefail
(($# >= 1)) || { sed -n '2,9p' "$0" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
out=$1
shift
bin=${VKRAYCAST:-$root/build/vkraycast}
[[ -x $bin ]] || { echo "build first (tools/demo.sh)" >&2; exit 2; }
ex=$root/tests/extremes/scenes
size=${SIZE:-160}
# One tile per frame (lavapipe's default, explicit for other devices): every variant
# pays the same one dispatch per batch; 160x160 so that shading, not lavapipe's fixed
# cost per dispatch, decides the times.
exec "$bin" tradeoff "$ex/S01_baseline.json" "$ex/S03_distance_1e3.json" "$ex/S07_closed_mesh_embree.json" \
  "$ex/S13_translate_xyz_1e5.json" "$ex/S16_acne_X1e4_E10.json" "$ex/S17_contact_X1e2_h1e-3.json" \
  "$ex/S21_many_spheres_D1e3.json" "$root/scenes/showcase.json" "$root/scenes/shadows.json" \
  --out "$out" --width "$size" --height "$size" --spp-list "${SPPS:-1,4,16,64}" --repeat "${REPEAT:-5}" \
  --reference-spp 256 --render-args="--tile $size --allow-outside-paths" "$@"
