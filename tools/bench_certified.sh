#!/usr/bin/env bash
# What --precision certified costs (docs/numerics.md §10, docs/performance.md): per scene,
# the frame time of GPU f32, GPU certified (f32 with certificates, the uncertified samples'
# samples again on the f64 CPU reference), GPU f64 and the CPU reference in f64, run in turn
# (f32, certified, f64, cpu f64, f32, ...) ROUNDS processes each with --repeat FRAMES; the
# share of samples left uncertified, of pixels re-rendered and of samples traced again
# in them (the uncertified ones, or whole pixels: base/certified_marks.h); and the pixels whose
# decisions plain f32 gets wrong against the CPU f64 reference, in the first sample or, by the
# digests of every sample's decisions, in any sample or bounce, which certified mode gets
# right (AOV compare).
# Usage: tools/bench_certified.sh [BIN] [SCENE...]   (default: build/vkraycast, scenes/*.json)
# Env: ROUNDS (3), FRAMES (3), ARGS (extra render options for every run).
set -euo pipefail
cd "$(dirname "$0")/.."
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
bin=${1:-build/vkraycast}
(($# > 0)) && shift
rounds=${ROUNDS:-3} frames=${FRAMES:-3}
scenes=("$@")
((${#scenes[@]})) || scenes=(scenes/*.json)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
modes=("--precision f32" "--precision certified" "--precision f64" "--backend cpu --precision f64")
echo "$bin; $(nproc) cores; $rounds processes each, --repeat $frames${ARGS:+, $ARGS}; medians of render_wall_ms"
echo
echo "| scene | f32 ms | certified ms | certified / f32 | f64 ms | CPU f64 ms | uncertified samples | pixels re-rendered | samples re-rendered | f32 decisions wrong | certified decisions wrong |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for s in "${scenes[@]}"; do
  for m in 0 1 2 3; do : >"$work/$m.txt"; done
  for ((r = 0; r < rounds; r++)); do
    for m in 0 1 2 3; do
      # shellcheck disable=SC2086
      "$bin" render "$s" -o "$work/out.exr" --repeat "$frames" --quiet --allow-outside-paths ${modes[$m]} ${ARGS:-} \
        --stats-json "$work/st.json"
      num render_wall_ms "$work/st.json" >>"$work/$m.txt"
    done
  done
  # One more process of each kind for the decisions (the AOVs: sample 0's, and every sample's digest).
  # shellcheck disable=SC2086
  "$bin" render "$s" -o "$work/ref.exr" --backend cpu --precision f64 --aov "$work/ref.aov.exr" --quiet \
    --allow-outside-paths ${ARGS:-}
  # shellcheck disable=SC2086
  "$bin" render "$s" -o "$work/f32.exr" --precision f32 --aov "$work/f32.aov.exr" --quiet --allow-outside-paths ${ARGS:-}
  # shellcheck disable=SC2086
  "$bin" render "$s" -o "$work/c.exr" --precision certified --aov "$work/c.aov.exr" --quiet --allow-outside-paths \
    ${ARGS:-} --stats-json "$work/c.json"
  # Pixels, each once: sample_mismatch (where both files have digests) already counts the
  # pixels whose first sample differs; files without digests have the first sample's alone.
  wrong() {
    "$bin" compare "$1" "$work/ref.aov.exr" --json >"$work/cmp.json" 2>/dev/null || true
    local any
    any=$(num sample_mismatch "$work/cmp.json")
    echo "${any:-$(($(num hit_mismatch "$work/cmp.json") + $(num object_mismatch "$work/cmp.json") + $(num shadow_mismatch "$work/cmp.json")))}"
  }
  samples=$(($(num width "$work/c.json") * $(num height "$work/c.json") * $(num samples_per_pixel "$work/c.json")))
  pixels=$(($(num width "$work/c.json") * $(num height "$work/c.json")))
  f32=$(median <"$work/0.txt") cert=$(median <"$work/1.txt")
  printf "| %s | %.1f | %.1f | %.2f | %.1f | %.1f | %.2f %% | %.2f %% | %.2f %% | %s | %s |\n" "$(basename "$s" .json)" \
    "$f32" "$cert" "$(awk -v x="$f32" -v y="$cert" 'BEGIN { print y / x }')" "$(median <"$work/2.txt")" \
    "$(median <"$work/3.txt")" "$(awk -v u="$(num samples_uncertified "$work/c.json")" -v n="$samples" 'BEGIN { print 100 * u / n }')" \
    "$(awk -v u="$(num pixels_rerendered "$work/c.json")" -v n="$pixels" 'BEGIN { print 100 * u / n }')" \
    "$(awk -v u="$(num samples_rerendered "$work/c.json")" -v n="$samples" 'BEGIN { print 100 * u / n }')" \
    "$(wrong "$work/f32.aov.exr")" "$(wrong "$work/c.aov.exr")"
done
