#!/usr/bin/env bash
# GPU against CPU, per scene (RENDER_ARGS are added to every render): renders each scene with AOVs as GPU f32, GPU f64, CPU f32
# and CPU f64, and compares GPU f32 / CPU f64 (the product against the accuracy
# reference), GPU f32 / CPU f32 (same arithmetic: driver and compiler effects only) and
# GPU f64 / CPU f64. Prints one markdown row per pair: PSNR, max error, pixels over 1e-3,
# first-sample decision mismatches (hit, object, shadow), the pixels whose decisions differ
# in any sample or bounce (the AOVs' digests), and each backend's render time.
#   tools/gpu_vs_cpu.sh [--check] VKRAYCAST OUTDIR SCENE...
# --check: exit 1 unless every pair is within the thresholds stated below.
set -euo pipefail
check=0
if [[ "${1:-}" == --check ]]; then check=1; shift; fi
bin=$1 out=$2
shift 2
mkdir -p "$out"
num() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2"; }

# Thresholds: `vkraycast compare --preset` (host/compare/compare_checks.c holds them
# with their reasons, docs/gpu-vs-cpu.md explains them): gpu f32 / cpu f64 is judged by
# gpu-vs-cpu, the same-arithmetic pairs by same-precision. The command for the first pair
# is the README's own compare example, so every example scene keeps it passing.
declare -A preset=([f32-f64]=gpu-vs-cpu [f32-f32]=same-precision [f64-f64]=same-precision)

failed=0
echo "| scene | pair | PSNR dB | max error | pixels > 1e-3 | hit / object / shadow mismatches | any sample | GPU ms | CPU ms |"
echo "|---|---|---|---|---|---|---|---|---|"
for scene in "$@"; do
  name=$(basename "$scene" .json)
  for backend in gpu cpu; do
    for p in f32 f64; do
      "$bin" render "$scene" -o "$out/$name-$backend-$p.exr" --aov "$out/$name-$backend-$p.aov.exr" \
        --backend $backend --precision $p --quiet --allow-outside-paths --stats-json "$out/$name-$backend-$p.json" ${RENDER_ARGS:-}
    done
  done
  for pair in f32-f64 f32-f32 f64-f64; do
    g=${pair%-*} c=${pair#*-}
    json=$out/$name-$pair.compare.json
    status=0
    "$bin" compare "$out/$name-gpu-$g.aov.exr" "$out/$name-cpu-$c.aov.exr" --preset "${preset[$pair]}" \
      --diff "$out/$name-$pair.heat.png" --json >"$json" || status=$?
    printf "| %s | gpu %s / cpu %s | %.1f | %.3g | %d | %d / %d / %d | %d | %.1f | %.1f |\n" "$name" "$g" "$c" \
      "$(num psnr "$json")" "$(num max_error "$json")" "$(num pixels_over "$json")" "$(num hit_mismatch "$json")" \
      "$(num object_mismatch "$json")" "$(num shadow_mismatch "$json")" "$(num sample_mismatch "$json")" \
      "$(num render_ms "$out/$name-gpu-$g.json")" "$(num render_ms "$out/$name-cpu-$c.json")"
    if ((status != 0)); then
      failed=1
      echo "THRESHOLD: $name gpu $g / cpu $c (--preset ${preset[$pair]}, exit $status):" >&2
      "$bin" compare "$out/$name-gpu-$g.aov.exr" "$out/$name-cpu-$c.aov.exr" --preset "${preset[$pair]}" >&2 || true
    fi
  done
done
((check == 0 || failed == 0))
