#!/usr/bin/env bash
# The fixed cost of one dispatch: each scene rendered as an 8x8 frame in one dispatch,
# f32 and f64, the median over --repeat frames of GPU time. A regression guard, not a test
# (no test reads a clock): on lavapipe this should stay well under a millisecond. A
# branch whose condition depends on uniform values alone once cost 5-9 ms here, in the
# f32 module only: Mesa 22.3's lavapipe inlined the values and recompiled the shader on
# every dispatch (docs/performance.md, "Where the time goes").
# Usage: tools/bench_dispatch.sh [SCENE...]   (default: scenes/*.json)
set -euo pipefail
cd "$(dirname "$0")/.."
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
scenes=("$@")
((${#scenes[@]})) || scenes=(scenes/*.json)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
echo "| scene | f32 ms per 8x8 dispatch | f64 ms per 8x8 dispatch |"
echo "|---|---|---|"
for s in "${scenes[@]}"; do
  row="| $(basename "$s" .json) |"
  for p in f32 f64; do
    build/vkraycast render "$s" -o "$work/o.exr" --width 8 --height 8 --tile 8 --spp 1 --repeat 21 --precision $p \
      --quiet --allow-outside-paths --stats-json "$work/st.json" 2>/dev/null
    row="$row $(num render_ms "$work/st.json") |"
  done
  echo "$row"
done
