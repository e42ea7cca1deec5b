#!/usr/bin/env bash
# Packs what a lent GPU machine lacks into .gpu/ (docs/porting.md, "Checklist for a real
# GPU"): a build configured for NVIDIA's ICD (build-gpu/, for ctest there), the libraries it
# needs that are not glibc's or the C++ runtime's (the Vulkan loader, the validation layer,
# assimp, OpenEXR, cJSON...), glslangValidator and spirv-val, Debian's spider OBJ for the
# user-like room, and Debian 12's libvulkan1 and libglvnd packages in .gl/ (the device
# tool's recipe). tools/gpu_device.sh unpacks it there. OpenImageIO stays behind: its
# libraries and theirs are 355 MB, over the 64 MiB a call may carry, so there JPEGs, PNGs
# with alpha and the other formats cannot be read or written; PNGs without alpha (read and
# written by the binary) and EXRs (vkraycast-exr.so) work, and so do textured scenes.
#   tools/gpu_bundle.sh            then carry ".gpu" and ".gl" and run tools/gpu_device.sh
# Env: ICD (/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json), DEVICE (NVIDIA), BASE (a
# commit: its binary and modules come along as build-gpu-base/, for gpu_device.sh's
# before/after part on the same GPU).
set -euo pipefail
cd "$(dirname "$0")/.."
icd=${ICD:-/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json}
cmake -S . -B build-gpu -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKRAYCAST_TEST_ICD="$icd" \
  -DVKRAYCAST_TEST_DEVICE="${DEVICE:-NVIDIA}" >/dev/null
cmake --build build-gpu -j"$(nproc)" >/dev/null
stage=$(mktemp -d)
base_src=$stage.src
trap 'rm -rf "$stage"; [[ -d $base_src ]] && git worktree remove --force "$base_src"' EXIT
mkdir -p "$stage"/{lib,layer,models,bin} .gpu .gl
base_bins=()
if [[ -n ${BASE:-} ]]; then # the baseline: the binary and its modules, nothing to test
  git worktree add -q --detach "$base_src" "$BASE"
  cmake -S "$base_src" -B "$base_src/b" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build "$base_src/b" -j"$(nproc)" --target vkraycast vkraycast-exr >/dev/null
  mkdir -p "$stage/build-gpu-base"
  cp "$base_src"/b/vkraycast "$base_src"/b/vkraycast-exr.so "$stage/build-gpu-base/"
  git -C "$base_src" rev-parse --short HEAD >"$stage/build-gpu-base/commit"
  base_bins=("$base_src"/b/vkraycast "$base_src"/b/vkraycast-exr.so)
fi
# The build tree without objects and generated headers; ctest's paths name /work/main.
tar -cf - --exclude=CMakeFiles --exclude='*.a' --exclude='*.spv.h' --exclude='*.o' --exclude=Testing build-gpu |
  tar -xf - -C "$stage"
if [[ -f build/Testing/Temporary/CTestCostData.txt ]]; then # longest tests first there
  mkdir -p "$stage/build-gpu/Testing/Temporary"
  cp build/Testing/Temporary/CTestCostData.txt "$stage/build-gpu/Testing/Temporary/"
fi
layer=/usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so
bins=(build-gpu/vkraycast build-gpu/vkraycast-exr.so build-gpu/vkraycast-mesh-import build-gpu/gen_mesh "$layer"
  /usr/bin/glslangValidator /usr/bin/spirv-val "${base_bins[@]}")
for f in "${bins[@]}"; do ldd "$f" | awk '$3 ~ /^\// {print $3}'; done | sort -u |
  grep -v -E '/(libc|libm|libpthread|libdl|librt|libstdc\+\+|libgcc_s|ld-linux-x86-64)\.so' |
  while read -r l; do cp -L "$l" "$stage/lib/"; done
cp "$layer" "$stage/lib/"
sed 's|"library_path": *"[^"]*"|"library_path": "/opt/vk/lib/libVkLayer_khronos_validation.so"|' \
  /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json >"$stage/layer/VkLayer_khronos_validation.json"
cp /usr/bin/glslangValidator /usr/bin/spirv-val "$stage/bin/"
spider=/usr/share/assimp/models/OBJ
cp "$spider"/spider.obj "$spider"/spider.mtl "$spider"/SpiderTex.jpg "$stage/models/"
find "$stage" -type f \( -name '*.so*' -o -perm -u+x \) -exec sh -c 'file "$1" | grep -q ELF && strip --strip-debug "$1"' _ {} \;
tar -cf - -C "$stage" . | xz -T"$(nproc)" -6 >.gpu/bundle.tar.xz
cp /usr/bin/xz .gpu/
# The loader and libglvnd as Debian packages, unpacked into / there (the device tool's recipe).
o=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
mkdir -p /tmp/amd64/partial
apt-get "${o[@]}" update >/dev/null
(cd .gl && apt-get "${o[@]}" download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null 2>&1)
du -sh .gpu .gl
