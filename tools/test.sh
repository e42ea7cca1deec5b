#!/usr/bin/env bash
# Quick start, command 2: set up, build, and run the whole test suite (ctest) on lavapipe
# with the Khronos validation layer on. A missing Vulkan device fails the suite.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
cd build
ctest --output-on-failure --timeout 600 -j"$(nproc)" "$@"
