#!/usr/bin/env bash
# The Slurm scripts on a real Slurm cluster of three nodes, each its own slurmd on this
# machine (tests/cluster/slurm_node.sh): the showcase as a 4-task job array plus the
# dependent merge (tools/slurm/submit.sh) equals a single render byte for byte. Then a
# shard that fails (its output name is taken by a folder): the merge runs anyway, writes
# nothing and names the shard and the command that renders it again;
# tools/slurm/resubmit.sh renders it alone (sbatch --array=2) and merges, and the image
# equals the single render. Then a node lost in the middle of a 6-task array (its slurmd
# and its running shard's processes killed): Slurm marks the node down and the task NODE_FAIL, the
# merge names the lost shard, resubmit.sh renders it on a surviving node, and the image
# equals the single render.
# The shards render the scene prepared once by a job before the array (prepare.sbatch).
# Usage: test_slurm.sh VKRAYCAST SCENES WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
tools=$here/../../tools/slurm
rm -rf "$work" && mkdir -p "$work"
if [[ $(id -u) != 0 ]]; then
  echo "skipped: slurmd starts jobs as their users, which needs root (CI runs as root)"
  exit 77
fi
for d in munged slurmctld slurmd sbatch; do
  command -v "$d" >/dev/null || { echo "FAIL: $d is missing: tools/setup.sh installs slurmctld, slurmd, slurm-client and munge"; exit 1; }
done
source "$here/../check.sh"
source "$here/slurm_node.sh"
slurm_start "$work/slurm" || { echo "FAIL: Slurm did not start"; exit 1; }
export VKRAYCAST=$bin
size=(--width 128 --height 96)
"$bin" render "$scenes/showcase.json" "${size[@]}" --quiet -o "$work/whole.png"

# The whole frame as 4 shards and a merge.
read -r array merge < <("$tools/submit.sh" -n 4 "$scenes/showcase.json" "$work/sharded.png" "${size[@]}")
slurm_wait "$array" "$merge"
why=ok
cmp -s "$work/sharded.png" "$work/whole.png" || why="the merged image differs from the single render: $(cat "$work"/sharded.png.parts/*.log 2>/dev/null | tail -5)"
check "4 shards and a merge" "$why"
rows=()
for i in 0 1 2 3; do rows+=("$(tr -d ' \n\t' <"$work/sharded.png.parts/part-$i.json" | sed -n 's/.*"region":\[0,\([0-9]*\),128,\([0-9]*\)\].*/\1-\2/p')"); done
why=ok
[[ ${#rows[@]} == 4 && -n ${rows[3]} ]] || why="shard regions: ${rows[*]}"
check "4 shards of rows ${rows[*]}" "$why"
why=ok
for i in 0 1 2 3; do
  grep -qF '"prepared":' "$work/sharded.png.parts/part-$i.json" || because "shard $i did not render the prepared scene"
done
[[ -s $work/sharded.png.parts/scene.vkrs ]] || because "no prepared scene in the parts' folder"
check "the shards rendered the scene prepared once" "$why"

# A shard that fails, found by the merge, rendered again alone.
parts=$work/failing.parts
mkdir -p "$parts/part-2.exr"
read -r array merge < <("$tools/submit.sh" -n 4 -p "$parts" "$scenes/showcase.json" "$work/failing.png" "${size[@]}")
slurm_wait "$array" "$merge"
log=$(cat "$parts"/vkraycast-merge-*.log 2>/dev/null)
why=ok
[[ ! -e $work/failing.png ]] || why="an image was written"
grep -qF "shard 2/4 is missing" <<<"$log" || why="$why; the merge did not name shard 2/4: $log"
grep -qF "resubmit.sh $parts 2" <<<"$log" || why="$why; no re-run command"
state=$(scontrol show job "${array}_2" 2>/dev/null | sed -n 's/.*JobState=\([A-Z]*\).*/\1/p')
[[ $state == FAILED ]] || why="$why; shard 2's task is $state, expected FAILED"
check "a failed shard is named" "$why"
rmdir "$parts/part-2.exr"
read -r shard merge < <("$tools/resubmit.sh" "$parts" 2)
slurm_wait "$shard" "$merge"
why=ok
cmp -s "$work/failing.png" "$work/whole.png" || why="after the re-run the image differs or is missing"
check "the shard rendered again alone, merged" "$why"

# A node lost in the middle of the array. The tasks are not requeued (--no-requeue: by
# default Slurm would requeue a batch task whose node failed, and the merge would wait
# for it), so the merge finds the shard missing and says how to render it again. On n2
# the binary is a wrapper that waits a minute before rendering, so that the node is lost
# while its shard is under way, whatever the machine's speed.
slow_bin=$work/vkraycast-slow-on-n2
printf '#!/usr/bin/env bash\n[[ ${SLURMD_NODENAME:-} == n2 && $1 == render ]] && sleep 60\nexec %q "$@"\n' \
  "$(realpath "$bin")" >"$slow_bin"
chmod +x "$slow_bin"
parts=$work/lost.parts
read -r array merge < <(VKRAYCAST=$slow_bin "$tools/submit.sh" -n 6 -p "$parts" -a "--no-requeue" \
  "$scenes/showcase.json" "$work/lost.png" "${size[@]}")
lost= task=
for _ in $(seq 600); do
  read -r task lost < <(squeue -h -w n2 -t RUNNING -o "%K %A" 2>/dev/null | awk '$1 != "N/A"' | head -1)
  [[ -n $lost ]] && break
  sleep 0.1
done
why=ok
if [[ -z $lost ]]; then
  why="no shard ran on n2: $(squeue -h -o '%K %N %T' 2>&1 | tr '\n' ' ')"
else
  sleep 1 # the task's processes have started
  slurm_kill_node n2
  slurm_wait "$array" "$merge"
  log=$(cat "$parts"/vkraycast-merge-*.log 2>/dev/null)
  state=$(scontrol show job "${array}_$task" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
  node=$(sinfo -h -n n2 -o %T 2>/dev/null)
  [[ ! -e $work/lost.png ]] || because "an image was written"
  grep -qF "shard $task/6 is missing" <<<"$log" || because "the merge did not name shard $task/6: $log"
  grep -qF "resubmit.sh $parts $task" <<<"$log" || because "no re-run command for shard $task"
  [[ $state == NODE_FAIL ]] || because "the lost shard's task is $state, expected NODE_FAIL"
  [[ $node == down* ]] || because "node n2 is '$node', expected down"
fi
check "a node lost mid-array: shard ${task:-?} named" "$why"
why=ok
if [[ -n $lost ]]; then
  read -r shard merge < <("$tools/resubmit.sh" "$parts" "$task")
  slurm_wait "$shard" "$merge"
  ran_on=$(scontrol show job "$shard" 2>/dev/null | sed -n 's/.* NodeList=\([^ ]*\).*/\1/p' | head -1)
  [[ $ran_on == n1 || $ran_on == n3 ]] || because "the re-run ran on '$ran_on', not a surviving node"
  cmp -s "$work/lost.png" "$work/whole.png" || because "after the re-run the image differs or is missing"
else
  why="no node was lost"
fi
check "the lost shard rendered on a surviving node, merged" "$why"
slurm_stop
finish
