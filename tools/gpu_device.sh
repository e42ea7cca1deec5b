#!/usr/bin/env bash
# On a lent GPU machine, from the repository's root, with .gpu and .gl carried
# (tools/gpu_bundle.sh): unpacks the bundle, then runs the checklist (tools/gpu_checklist.sh),
# what certified mode costs (tools/bench_certified.sh) and the test suite, each under a time
# limit so that everything ends inside one call, and leaves the reports in OUT (at most 8
# files: the device tool's limit).
#   OUT=$OUT tools/gpu_device.sh
# Env: T_CHK (180), T_AB (90), T_CERT (100), T_CTEST (180) seconds; AB_ROUNDS (5); AB_SCENES
# (scenes/showcase.json scenes/mesh.json); AB_TILES ("default 1024 512 256"); AB_FRAMES (6;
# 1 times a user's one-image process, the write included); PARTS
# ("checklist ab certified ctest"; ab runs where the bundle has a baseline: BASE=commit
# tools/gpu_bundle.sh); CTEST_ARGS (added to ctest's).
set -u
root=$PWD out=${OUT:?set OUT}
t0=$(date +%s)
el() { echo "[$(($(date +%s) - t0)) s] $*" | tee -a "$out/run.log"; }
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
rm -rf /opt/vk build-gpu build-gpu-base && mkdir -p /opt/vk
tar -I "$root/.gpu/xz" -xf .gpu/bundle.tar.xz -C /opt/vk || { el "cannot unpack .gpu/bundle.tar.xz"; exit 1; }
mv /opt/vk/build-gpu "$root/build-gpu"
[[ -d /opt/vk/build-gpu-base ]] && mv /opt/vk/build-gpu-base "$root/build-gpu-base"
# The build and its tests name /work/main.
[[ -e /work/main ]] || { mkdir -p /work && ln -s "$root" /work/main; }
# A library the machine has is the machine's.
ldconfig -p | awk 'NR > 1 {print $1}' | sort -u >/tmp/syslibs.txt
for f in /opt/vk/lib/*; do
  b=$(basename "$f")
  [[ $b != libVkLayer* ]] && grep -qxF "$b" /tmp/syslibs.txt && rm "$f"
done
icd=${ICD:-/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json}
# Keep the machine's LD_LIBRARY_PATH: NVIDIA's ICD finds its own libraries through it, and
# without them the loader reports "Could not get 'vkCreateInstance'" for libGLX_nvidia.
export VK_DRIVER_FILES=$icd VK_ICD_FILENAMES=$icd LD_LIBRARY_PATH=/opt/vk/lib:${LD_LIBRARY_PATH:-} \
  VK_LAYER_PATH=/opt/vk/layer XDG_RUNTIME_DIR=/tmp XDG_CACHE_HOME=/tmp/cache PATH=/opt/vk/bin:$PATH \
  SPIDER_DIR=/opt/vk/models
{ nvidia-smi -L; uname -r; nproc; grep PRETTY /etc/os-release; } >>"$out/run.log" 2>&1
bin=$root/build-gpu/vkraycast
"$bin" devices 2>&1 | tee -a "$out/run.log"
parts=${PARTS:-checklist ab certified ctest}
if [[ $parts == *checklist* ]]; then
  el checklist
  rm -rf /tmp/chk
  ROUNDS=3 FRAMES=5 VKRAYCAST=$bin timeout "${T_CHK:-180}" tools/gpu_checklist.sh /tmp/chk scenes/showcase.json \
    scenes/mesh.json scenes/csg.json scenes/room.json scenes/teapot.json /tmp/chk/user_room/user_room.json \
    >"$out/checklist.out" 2>&1
  el "checklist: exit $?"
  (cd /tmp/chk && tar -czf "$out/checklist.tgz" --exclude='*.png' --exclude='*.exr' --exclude=cache .)
fi
if [[ $parts == *ab* && -x build-gpu-base/vkraycast ]]; then
  # The 3840 x 2160 frame against the baseline build, default tiling and smaller tiles (item 8).
  el "ab: A = $(cat build-gpu-base/commit), B = this build"
  # PNG: the shader's 8-bit encoding. The baseline borrows this build's mesh importer.
  # shellcheck disable=SC2016
  VKRAYCAST_MESH_IMPORTER=$root/build-gpu/vkraycast-mesh-import EXT=png timeout "${T_AB:-90}" bash -c '
    for tile in ${AB_TILES:-default 1024 512 256}; do
      [[ $tile == default ]] && tile="" || tile="--tile $tile"
      # shellcheck disable=SC2086
      ROUNDS=${AB_ROUNDS:-5} FRAMES=${AB_FRAMES:-6} ARGS="--width 3840 --height 2160 --spp 1 $tile" \
        tools/bench_ab.sh build-gpu-base/vkraycast "$1" ${AB_SCENES:-scenes/showcase.json scenes/mesh.json}; echo
    done' _ "$bin" >"$out/ab.md" 2>&1
  el "ab: exit $?"
fi
if [[ $parts == *certified* ]]; then
  el certified
  ROUNDS=3 FRAMES=3 timeout "${T_CERT:-100}" tools/bench_certified.sh "$bin" scenes/showcase.json scenes/mesh.json \
    scenes/room.json scenes/teapot.json >"$out/certified.md" 2>&1
  el "certified: exit $?"
fi
if [[ $parts == *ctest* ]]; then
  el ctest
  # shellcheck disable=SC2086
  (cd build-gpu && timeout "${T_CTEST:-180}" ctest -j"$(nproc)" --output-on-failure -E '^slurm$' ${CTEST_ARGS:-} \
    >"$out/ctest.log" 2>&1)
  el "ctest: exit $?"
fi
el "done"
