# Sourced by the Embree benchmarks (tools/bench_vs_embree.sh, tools/bench_embree_harness.sh)
# after they cd to the repository root: installs libembree-dev where it is missing (the
# yardstick only; vkraycast never depends on Embree), builds bench_embree and gen_mesh,
# picks lavapipe, reads FRAMES (6), ROUNDS (3) and THREADS (nproc) into frames, rounds
# and threads, and makes the scratch folder $work, removed on exit.
if ! dpkg-query -W -f='${Status}' libembree-dev 2>/dev/null | grep -q 'install ok installed'; then
  [ "$(id -u)" -eq 0 ] && sudo= || sudo=sudo
  $sudo apt-get install -y -qq --no-install-recommends libembree-dev >&2
fi
tools/setup.sh
cmake -S . -B build >/dev/null && cmake --build build --target bench_embree gen_mesh -j"$(nproc)" >&2
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json}
export VK_ICD_FILENAMES=$VK_DRIVER_FILES XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
frames=${FRAMES:-6} rounds=${ROUNDS:-3} threads=${THREADS:-$(nproc)}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tools/bench_common.sh
