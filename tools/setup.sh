#!/usr/bin/env bash
# Installs (when missing) the Debian 12 packages vkraycast builds and tests with, then
# configures and builds build/vkraycast. Idempotent: with everything installed it only
# runs the incremental build. Used by tools/demo.sh and tools/test.sh (the README's two
# commands) and therefore by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config python3
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools # spirv-val for the tests; SPIRV-Tools' optimizer, which the
                            # renderer links (host/gpu/spirv_specialize.h)
  libopenimageio-dev openimageio-tools
  libopenexr-dev # EXRs read and written without OpenImageIO's 260 libraries (host/image/exr_*.cpp)
  libpng-dev zlib1g-dev # PNGs written without them (host/image/png_write.c)
  libcjson-dev libxxhash-dev
  libassimp-dev assimp-testmodels
  clang libclang-rt-14-dev
  slurmctld slurmd slurm-client munge
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

build_type=${VKRAYCAST_BUILD_TYPE:-RelWithDebInfo}
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE="$build_type" >&2
fi
cmake --build build -j"$(nproc)" >&2
