#!/usr/bin/env bash
# Issue 48's yardstick of a scene a user writes from the docs: bench/user_room.json (two
# planes, a mirror sphere, a tinted sphere, Debian's spider OBJ from assimp-testmodels, two
# coloured point lights, 640 x 400, 4 spp), the GPU path against its CPU twin, both in
# f32, interleaved processes (tools/bench_ab.sh: medians of the steady frame, frames
# 2..FRAMES, with process CPU time beside it). Extra arguments go to both sides (e.g.
# "--shadows off", "--reflection-depth 0").
#   tools/bench_user_room.sh [RENDER_ARGS...]     Env: ROUNDS (5), FRAMES (3)
set -euo pipefail
cd "$(dirname "$0")/.."
spider=/usr/share/assimp/models/OBJ
[[ -f $spider/spider.obj ]] || { echo "needs $spider/spider.obj (Debian's assimp-testmodels)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$spider"/spider.obj "$spider"/spider.mtl "$spider"/SpiderTex.jpg bench/user_room.json "$work"/
ARGS="--precision f32 $*" ARGS_B="--backend cpu" tools/bench_ab.sh build/vkraycast build/vkraycast "$work/user_room.json"
