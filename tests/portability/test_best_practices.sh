#!/usr/bin/env bash
# Best practices for NVIDIA and AMD (docs/porting.md, "Best practices"): every GPU path
# renders with the Khronos layer's best-practice checks and both vendors' checks on, and
# vkraycast counts every warning they give (exit 3 on any). Advice that cannot apply is
# printed as "not counted" with the reason (host/gpu/vk_context.c, excused); at least one
# such line proves the checks ran. The memory comes in one block per use (vk_memory.h):
# the device's, and with staging (forced, or a discrete GPU's own) the upload and readback
# ones.
#   test_best_practices.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
mkdir -p "$work"
source "$(dirname "$0")/../check.sh"
export VKRAYCAST_VALIDATION=1
export VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_BEST_PRACTICES_EXT:VALIDATION_CHECK_ENABLE_VENDOR_SPECIFIC_NVIDIA:VALIDATION_CHECK_ENABLE_VENDOR_SPECIFIC_AMD

# NAME SCENE MAX_BLOCKS [render args...]
run() {
  local name=$1 scene=$2 blocks=$3 why=ok
  shift 3
  "$bin" render "$scene" -o "$work/$name.exr" --width 160 --height 100 --stats-json "$work/$name.json" --quiet \
    --allow-outside-paths "$@" 2>"$work/$name.err"
  local rc=$?
  [[ $rc == 0 ]] || because "exit status $rc: $(grep -m3 'validation' "$work/$name.err" | cut -c1-300)"
  grep -q "validation (not counted: " "$work/$name.err" || because "no best-practice message at all: were the checks on?"
  local n
  n=$(json_num memory_blocks "$work/$name.json")
  grep -q '"staging":[[:space:]]*true' "$work/$name.json" && blocks=3
  [[ -n $n && $n -le $blocks ]] || because "$n device memory blocks, expected at most $blocks"
  check "$name" "$why"
}

run image "$scenes/showcase.json" 1
run texel "$scenes/showcase.json" 1 --scene-buffers texel
run storage "$scenes/showcase.json" 1 --scene-buffers storage
run staging "$scenes/showcase.json" 3 --staging
run f64 "$scenes/showcase.json" 1 --precision f64
run aov "$scenes/showcase.json" 1 --aov "$work/aov_out.exr"
run tiles "$scenes/showcase.json" 1 --tile 48 --spp 16
run generic "$scenes/csg.json" 1 --pipeline generic
run quadrics "$scenes/room.json" 1
run mesh_staging "$scenes/mesh.json" 3 --staging --scene-buffers storage --aov "$work/mesh_aov_out.exr"

# Only the three excuses docs/porting.md explains were used.
grep -h "validation (not counted" "$work"/*.err | sed 's/.*\[ \([^ ]*\) \].*/\1/' | sort -u > "$work/excused"
while read -r id; do
  case $id in
    UNASSIGNED-BestPractices-vkCreateInstance-specialuse-extension-debugging | \
      UNASSIGNED-BestPractices-AllocateMemory-SetPriority | UNASSIGNED-BestPractices-Pipeline-SortAndBind) ;;
    *) check "excused $id" "an excuse not in docs/porting.md's list" ;;
  esac
done < "$work/excused"
finish
