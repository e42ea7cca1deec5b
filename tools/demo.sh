#!/usr/bin/env bash
# Quick start, command 1: set up, build, and render the showcase scene to out/showcase.png.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
mkdir -p out
build/vkraycast render scenes/showcase.json -o out/showcase.png "$@"
echo "wrote out/showcase.png"
