#!/usr/bin/env bash
# The checklist of docs/porting.md ("Checklist for a real GPU"), items 1, 3-6 and 8-12, plus the
# speed of the GPU against the CPU reference on the same machine. Run it on the machine with
# the GPU, with VK_DRIVER_FILES naming that GPU's ICD manifest (it refuses lavapipe, whose
# results CI has already). Item 2 is `ctest -L gpu` in a build configured with
# -DVKRAYCAST_TEST_ICD and -DVKRAYCAST_TEST_DEVICE; item 7 is tools/tradeoff.sh.
#   tools/gpu_checklist.sh OUTDIR [BENCH_SCENE...]
# Env: VKRAYCAST (build/vkraycast), ROUNDS (5) processes per bench figure (0: no speed
# table), FRAMES (5), BENCH_ARGS (added to every timed render), SPIDER_DIR (where
# spider.obj is: Debian's assimp-testmodels, /usr/share/assimp/models/OBJ).
# Exit 1 if any item fails; the report is OUTDIR/checklist.md.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${VKRAYCAST:-$root/build/vkraycast}
out=$1
shift
mkdir -p "$out"
report=$out/checklist.md
: >"$report"
rounds=${ROUNDS:-5} frames=${FRAMES:-5}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} XDG_CACHE_HOME=$out/cache
num() { sed -n "s/.*\"$1\":[[:space:]]*\"\{0,1\}\([-0-9.e+A-Za-z_ ]*\).*/\1/p" "$2" | head -1; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
say() { echo "$*" | tee -a "$report"; }
failed=0
verdict() { # NAME OK DETAIL
  if [[ $2 == 1 ]]; then say "- [x] $1: $3"; else say "- [ ] **FAIL** $1: $3"; failed=1; fi
}

[[ -n ${VK_DRIVER_FILES:-} ]] || { echo "set VK_DRIVER_FILES to the GPU's ICD manifest" >&2; exit 2; }
export VK_ICD_FILENAMES=$VK_DRIVER_FILES
"$bin" devices >"$out/devices.txt" 2>&1
if grep -q llvmpipe "$out/devices.txt"; then echo "this is lavapipe; CI covers it" >&2; exit 2; fi

say "# GPU checklist: $(sed -n 2p "$out/devices.txt" | sed 's/  */ /g')"
say ""
say "\`$(basename "$bin") --version\`: $("$bin" --version 2>&1 | head -1); $(nproc) CPU cores"
say ""
say '```'
tee -a "$report" <"$out/devices.txt"
say '```'
say ""

# 1. The device, its type and f64.
type=$(sed -n 2p "$out/devices.txt")
verdict "1. devices" "$([[ $type == *discrete* || $type == *integrated* ]] && echo 1)" "$type"

# 3. Best practices, with and without staging: no counted message.
bp=VK_VALIDATION_FEATURE_ENABLE_BEST_PRACTICES_EXT:VALIDATION_CHECK_ENABLE_VENDOR_SPECIFIC_NVIDIA:VALIDATION_CHECK_ENABLE_VENDOR_SPECIFIC_AMD
for staging in "" --staging; do
  log=$out/best_practices${staging:+_staging}.log
  VKRAYCAST_VALIDATION=1 VK_LAYER_ENABLES=$bp "$bin" render "$root/scenes/showcase.json" -o "$out/bp.png" $staging \
    --width 320 --height 200 >"$log" 2>&1
  rc=$?
  counted=$(grep -c "^validation" "$log" | head -1)
  excused=$(grep -c "not counted" "$log" | head -1)
  prio=$(grep -c "SetPriority" "$log" | head -1)
  verdict "3. best practices ${staging:-(device-local)}" "$((rc == 0 && prio == 0))" \
    "exit $rc, $counted validation lines ($excused not counted), SetPriority excuses: $prio"
done

# 4. The plan: subgroup size, workgroup, loop budget, memory blocks (at a size where no
# buffer takes a block of its own: vk_memory.h).
"$bin" render "$root/scenes/showcase.json" -o "$out/showcase.png" --width 160 --height 100 --quiet \
  --stats-json "$out/showcase.json"
sg=$(num subgroup_size "$out/showcase.json") wx=$(num workgroup_x "$out/showcase.json")
wy=$(num workgroup_y "$out/showcase.json") lb=$(num loop_budget "$out/showcase.json")
mb=$(num memory_blocks "$out/showcase.json")
want_wy=$(((sg > 64 ? sg : 64) / 8))
verdict "4. plan" "$((wx == 8 && wy == want_wy && lb == 49152 && mb == 3))" \
  "subgroup $sg, workgroup ${wx}x$wy (want 8x$want_wy), loop budget $lb (want 49152), memory blocks $mb (want 3)"

# 5. GPU against the CPU reference, f32 and f64, within docs/gpu-vs-cpu.md's thresholds.
if "$root/tools/gpu_vs_cpu.sh" --check "$bin" "$out/gpu_vs_cpu" "$root"/scenes/*.json >"$out/gpu_vs_cpu.md" 2>"$out/gpu_vs_cpu.err"; then
  verdict "5. gpu_vs_cpu --check" 1 "every example scene within the thresholds (gpu_vs_cpu.md)"
else
  verdict "5. gpu_vs_cpu --check" 0 "$(tr '\n' ';' <"$out/gpu_vs_cpu.err" | cut -c1-600)"
fi

# 6. The tile model on a watchdog-bound device: no dispatch over the budget.
"$bin" render "$root/scenes/mesh.json" -o "$out/mesh4096.exr" --width 4096 --height 4096 --quiet \
  --allow-outside-paths --stats-json "$out/mesh4096.json"
md=$(num max_dispatch_ms "$out/mesh4096.json") ob=$(num dispatches_over_budget "$out/mesh4096.json")
verdict "6. tiles at 4096x4096" "$(awk -v m="$md" -v o="$ob" 'BEGIN { print (m <= 100 && o == 0) }')" \
  "max_dispatch_ms $md, dispatches_over_budget $ob, $(num dispatches "$out/mesh4096.json") dispatches, budget $(num tile_budget_ms "$out/mesh4096.json") ms"

# 8. The frame, not just the kernel: the shader's 8-bit encoding against f32 sums.
for enc in auto off; do
  "$bin" render "$root/scenes/showcase.json" -o "$out/frame_$enc.png" --width 3840 --height 2160 --spp 1 \
    --repeat 5 --quiet --gpu-encode "$enc" --stats-json "$out/frame_$enc.json"
done
same=$(cmp -s "$out/frame_auto.png" "$out/frame_off.png" && echo 1)
for enc in auto off; do
  j=$out/frame_$enc.json
  say "  - \`--gpu-encode $enc\`: readback_bytes $(num readback_bytes "$j"), readback_submits $(num readback_submits "$j"), \
readback_overlapped $(num readback_overlapped "$j") of $(num tiles "$j") tiles, bands_overlapped $(num bands_overlapped "$j"), \
band_overlapped_ms $(num band_overlapped_ms "$j"), band_hidden_ms $(num band_hidden_ms "$j"), readback_ms $(num readback_ms "$j"), render_wall_ms $(num render_wall_ms "$j"), render_ms $(num render_ms "$j"), write_ms $(num write_ms "$j"), \
gpu_encoded $(num gpu_encoded "$j"), readback_cached $(num readback_cached "$j")"
done
cached=$(num readback_cached "$out/frame_auto.json")
verdict "8. frame at 3840x2160" "$([[ $same == 1 && $cached == true ]] && echo 1)" \
  "PNGs $([[ $same == 1 ]] && echo identical || echo DIFFER), readback_cached $cached"
# Tiles of 512: through staging the host reads each tile while the next one's dispatch runs.
"$bin" render "$root/scenes/showcase.json" -o "$out/frame_tiles.png" --width 3840 --height 2160 --spp 1 \
  --repeat 5 --quiet --tile 512 --stats-json "$out/frame_tiles.json"
j=$out/frame_tiles.json
say "  - \`--tile 512\`: staging $(num staging "$j"), readback_overlapped $(num readback_overlapped "$j") of $(num tiles "$j") tiles, \
bands_overlapped $(num bands_overlapped "$j"), readback_ms $(num readback_ms "$j"), render_wall_ms $(num render_wall_ms "$j"), render_ms $(num render_ms "$j")"
cmp -s "$out/frame_tiles.png" "$out/frame_auto.png" || say "  - \`--tile 512\`: the PNG DIFFERS from the whole frame's"
rm -f "$out"/frame_*.png

# 9. Learned batches under the time budget, and the same image with a fixed plan.
room=$out/user_room
mkdir -p "$room"
cp "$root/bench/user_room.json" "$room/"
cp "${SPIDER_DIR:-/usr/share/assimp/models/OBJ}"/spider.{obj,mtl} "${SPIDER_DIR:-/usr/share/assimp/models/OBJ}"/SpiderTex.jpg "$room/"
"$bin" render "$room/user_room.json" -o "$room/a.exr" --width 3840 --height 2160 --spp 64 --repeat 3 --quiet \
  --stats-json "$out/room64.json"
j=$out/room64.json
"$bin" render "$room/user_room.json" -o "$room/b.exr" --width 3840 --height 2160 --spp 64 --quiet \
  --plan-budget "$(num loop_budget "$j")" --tile 256
bs=$(num batch_samples "$j") be=$(num batch_samples_end "$j") md=$(num max_dispatch_ms "$j")
ob=$(num dispatches_over_budget "$j")
# The pixels, not the files: an EXR's header records the options it was rendered with.
"$bin" compare "$room/a.exr" "$room/b.exr" --json >"$out/room64_cmp.json" 2>&1
same=$([[ $(num max_error "$out/room64_cmp.json") == 0 ]] && echo 1)
verdict "9. learned batches" "$(awk -v s="$bs" -v e="$be" -v m="$md" -v o="$ob" -v same="$same" \
  'BEGIN { print (e > s && m <= 100 && o == 0 && same == 1) }')" \
  "batch_samples $bs -> $be, max_dispatch_ms $md, dispatches_over_budget $ob, $(num dispatches "$j") dispatches, \
render_wall_ms $(num render_wall_ms "$j"), image $([[ $same == 1 ]] && echo same || echo DIFFERS) with --plan-budget and --tile 256"
rm -f "$room"/*.exr

# 10. Certified mode's re-render in f64 on the GPU against the CPU.
for s in showcase mesh; do
  line=""
  for rr in gpu cpu; do
    j=$out/cert_${s}_$rr.json
    "$bin" render "$root/scenes/$s.json" -o "$out/cert.exr" --precision certified --certified-rerender "$rr" \
      --repeat 3 --quiet --stats-json "$j" || line+=" $rr: FAILED"
    line+=" $rr: rerender_ms $(num rerender_ms "$j"), render_wall_ms $(num render_wall_ms "$j"),"
  done
  j=$out/cert_${s}_gpu.json
  say "  - $s certified, samples_uncertified $(num samples_uncertified "$j") (first at the hit/shadow/bounce \
$(num samples_uncertified_hit "$j")/$(num samples_uncertified_shadow "$j")/$(num samples_uncertified_bounce "$j")):$line"
done
rm -f "$out/cert.exr"
verdict "10. certified re-render" "$([[ -n $(num rerender_ms "$out/cert_mesh_gpu.json") ]] && echo 1)" \
  "figures above; ctest -R certified judges the decisions"

# 11. The eye buffer on a sphere cloud: steady frame with it on over off.
"$root/tools/gen_sphere_cloud.sh" 3000 >"$out/cloud.json"
for eb in off on; do
  : >"$out/eb_$eb.txt"
  for ((r = 0; r < 3; r++)); do
    "$bin" render "$out/cloud.json" -o "$out/cloud.png" --eye-buffer "$eb" --repeat 5 --quiet \
      --stats-json "$out/eb.json" && num render_wall_ms "$out/eb.json" >>"$out/eb_$eb.txt"
  done
done
off=$(median <"$out/eb_off.txt") on=$(median <"$out/eb_on.txt")
verdict "11. eye buffer" "$([[ -n $off && -n $on ]] && echo 1)" \
  "3000 spheres: off $off ms, on $on ms, on/off $(awk -v a="$on" -v b="$off" 'BEGIN { printf "%.2f", a / b }')"
rm -f "$out/cloud.png" "$out/eb.json" "$out"/eb_*.txt

# 12. Specialization on the host against the driver's: same image, pipeline time.
line="" ok=1
for sc in host driver; do
  for run in 1 2; do
    "$bin" render "$root/scenes/showcase.json" -o "$out/spec_$sc.png" --spec-constants "$sc" --quiet \
      --stats-json "$out/spec.json"
    line+=" $sc run $run pipeline_ms $(num pipeline_ms "$out/spec.json"),"
  done
done
cmp -s "$out/spec_host.png" "$out/spec_driver.png" || ok=0
verdict "12. spec constants" "$ok" "PNGs $([[ $ok == 1 ]] && echo identical || echo DIFFER);$line"
rm -f "$out"/spec_*.png "$out/spec.json"

((rounds > 0)) || exit $failed
# Speed: the GPU in f32 and f64 against the CPU reference (all cores) on the same scenes.
say ""
say "## Speed: median of $rounds processes, each the median of frames 2..$frames (\`--repeat $frames\`)"
say ""
say "Wall ms per frame (readback included); GPU f32 kernel ms from timestamps."
say ""
say "| scene | objects | GPU f32 ms | GPU f32 kernel ms | GPU f64 ms | CPU f32 ms | CPU f64 ms | GPU f32 Mrays/s | CPU f32 Mrays/s | GPU f32 first frame ms | dispatches |"
say "|---|---|---|---|---|---|---|---|---|---|---|"
bench=("$@")
((${#bench[@]})) || bench=("$root"/scenes/*.json)
for s in "${bench[@]}"; do
  row=()
  for cfg in "gpu f32" "gpu f64" "cpu f32" "cpu f64"; do
    set -- $cfg
    : >"$out/b.txt"
    for ((r = 0; r < rounds; r++)); do
      "$bin" render "$s" -o "$out/b.exr" --backend "$1" --precision "$2" --repeat "$frames" --quiet \
        --allow-outside-paths --stats-json "$out/b.json" ${BENCH_ARGS:-} || { echo "x x x x x x" >>"$out/b.txt"; continue; }
      echo "$(num render_wall_ms "$out/b.json") $(num mrays_per_s "$out/b.json") $(num first_frame_ms "$out/b.json") \
$(num dispatches "$out/b.json") $(($(num spheres "$out/b.json") + $(num triangles "$out/b.json") + $(num quadrics "$out/b.json"))) \
$(num render_ms "$out/b.json")" >>"$out/b.txt"
    done
    for c in 1 2 3 4 5 6; do row+=("$(awk -v c=$c '{print $c}' "$out/b.txt" | median)"); done
  done
  if [[ ${row[0]} == x || ${row[4]} == x ]]; then say "| $(basename "$s" .json) | render failed |"; continue; fi
  # row: per config 6 columns (wall, mrays, first, dispatches, objects, kernel).
  say "$(printf "| %s | %s | %.2f | %.2f | %.2f | %.1f | %.1f | %.1f | %.1f | %.1f | %s |" "$(basename "$s" .json)" "${row[4]}" \
    "${row[0]}" "${row[5]}" "${row[6]}" "${row[12]}" "${row[18]}" "${row[1]}" "${row[13]}" "${row[2]}" "${row[3]}")"
done
rm -f "$out/b.exr" "$out/b.json" "$out/b.txt" "$out/bp.png"
exit $failed
