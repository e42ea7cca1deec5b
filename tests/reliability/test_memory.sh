#!/usr/bin/env bash
# Memory per frame is bounded (issue 13, class 8): `render --repeat N` on a tiny image
# must not grow the process's peak RSS with N. Generated over the paths a frame can take
# (the three kinds of scene buffers, staging with AOVs, f64, the CPU backend): peak RSS at 300
# frames may exceed that at 1 frame by at most 16 MiB (a leak of 1 MiB a frame, as once
# reported, would show 300).
# Usage: test_memory.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
# AddressSanitizer keeps freed memory in quarantine, which would look like growth.
# (grep without -q: with pipefail, an early exit would SIGPIPE ldd and fail the test.)
if ldd "$bin" 2>/dev/null | grep libasan >/dev/null; then
  export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}quarantine_size_mb=0"
fi
rss() { # args... -> peak RSS in KiB
  "$bin" render "$scenes/showcase.json" -o "$work/o.png" --width 8 --height 8 --quiet --stats-json "$work/s.json" "$@" ||
    { echo -1; return; }
  sed -n 's/.*"peak_rss_mib":[[:space:]]*\([0-9.]*\).*/\1/p' "$work/s.json" | awk '{printf "%d", $1 * 1024}'
}
while IFS='|' read -r name args; do
  args=${args//WORK/$work}
  # shellcheck disable=SC2086
  one=$(rss --repeat 1 $args) many=$(rss --repeat 300 $args)
  why=ok
  if ((one < 0 || many < 0)); then why="render failed"
  elif ((many - one > 16384)); then why="peak RSS $one KiB at 1 frame, $many KiB at 300"
  fi
  check "$name: $one KiB at 1 frame, $many KiB at 300" "$why"
done <<'CASES'
gpu, storage texel buffers|
gpu, uniform texel buffers|--scene-buffers texel
gpu, storage buffers|--scene-buffers storage
gpu, staging and AOVs|--staging --aov WORK/o.aov.exr
gpu, f64|--precision f64
gpu, generic pipeline|--pipeline generic
cpu|--backend cpu
CASES
finish
