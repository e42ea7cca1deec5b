#!/usr/bin/env bash
# Quick start, command 2: set up, build, and run the whole test suite (ctest) on lavapipe
# with the Khronos validation layer on (synchronization validation included). A missing
# Vulkan device fails the suite. Then the same suite again in an AddressSanitizer +
# UndefinedBehaviorSanitizer build compiled by clang (build-asan/: the first pass is GCC's,
# so every change is built by both compilers), and a short libFuzzer run of each input
# parser (tools/fuzz.sh). VKRAYCAST_QUICK=1 skips those two (local iteration only;
# CI runs everything).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
(cd build && ctest --output-on-failure --timeout 900 -j"$(nproc)" "$@")
if [ "${VKRAYCAST_QUICK:-0}" = 1 ]; then exit 0; fi
echo "== the suite under AddressSanitizer and UndefinedBehaviorSanitizer (build-asan/)" >&2
if [ ! -f build-asan/CMakeCache.txt ]; then
  CC=clang CXX=clang++ cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKRAYCAST_SANITIZE=ON >&2
fi
cmake --build build-asan -j"$(nproc)" >&2
# Under the sanitizers, what gates numbers rather than code paths runs in part or not at
# all, to keep the suite's time in bounds: the extremes suite runs four of its cases (S01:
# every measurement path, S09: 1,000-triangle fans, S20: quadrics, S21: 2,000 spheres;
# S23's planes and transforms run under the sanitizers in the shapes_ tests);
# gpu_vs_cpu (tolerances between backends on full-size renders: gpu_render_examples
# test renders the same scenes on both backends under ASan), parse_scale (parsing time;
# the fuzzers and strict_input run the parsers under ASan) and memory_per_frame (peak RSS,
# which ASan's own allocator decides) run only in the pass above, and so does slurm (it
# tests the Slurm scripts; `merge` runs the same render and merge code under ASan), and
# so do minimum_device and extreme_min_f64 (images and gates on the minimum device;
# best_practices runs the allocator and every buffer path under ASan).
(cd build-asan && ctest --output-on-failure --timeout 1800 -j"$(nproc)" \
  -E 'extreme_S(0[2-8]|1[0-9]|23)|extreme_min|minimum_device|gpu_vs_cpu|parse_scale|memory_per_frame|slurm' "$@")
if [ -x tools/fuzz.sh ]; then tools/fuzz.sh; fi
