#!/usr/bin/env bash
# Renders a frame on a Slurm cluster: a job that prepares the scene once (packs it and
# builds its BVH into PARTS/scene.vkrs), N shards as one job array that depends on it (one
# task per shard, each on its own device, each mapping the prepared scene), then a merge
# that depends on them (docs/cluster.md).
#   tools/slurm/submit.sh [-n N] [-p PARTS] [-a "SBATCH OPTIONS"] [-P] SCENE OUT [render options]
# PARTS (default OUT.parts/) must lie on a filesystem every node sees. -a passes options
# to every sbatch call (--partition, --gres=gpu:1, --time, --hold, ...). -P: no prepare
# job; every shard parses the scene (a SCENE that is a .vkrs file is never prepared
# again). Prints the array job's ID and the merge job's ID. The parts' settings are
# written to PARTS/job.env, which resubmit.sh reads to render one shard again.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
n=4 parts= sbatch_args= prepare=1
while getopts "n:p:a:P" o; do
  case $o in
    n) n=$OPTARG ;;
    p) parts=$OPTARG ;;
    a) sbatch_args=$OPTARG ;;
    P) prepare= ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
(($# >= 2)) || { sed -n '2,12p' "$0" >&2; exit 2; }
scene=$(realpath "$1") out=$(realpath -m "$2")
shift 2
parts=$(realpath -m "${parts:-$out.parts}")
bin=$(realpath "${VKRAYCAST:-$here/../../build/vkraycast}")
mkdir -p "$parts"
[[ $scene != *.vkrs ]] || prepare=
prepared=
[[ -z $prepare ]] || prepared=$parts/scene.vkrs
cat >"$parts/job.env" <<ENV
export VKRAYCAST=$(printf %q "$bin")
export VKRAYCAST_SCENE=$(printf %q "$scene")
export VKRAYCAST_PREPARED=$(printf %q "$prepared")
export VKRAYCAST_PARTS=$(printf %q "$parts")
export VKRAYCAST_OUTPUT=$(printf %q "$out")
export VKRAYCAST_SHARDS=$n
export VKRAYCAST_RENDER_ARGS=$(printf %q "$*")
export VKRAYCAST_SLURM_TOOLS=$(printf %q "$here")
VKRAYCAST_SBATCH_ARGS=$(printf %q "$sbatch_args")
ENV
# shellcheck source=/dev/null
source "$parts/job.env"
after=()
if [[ -n $prepared ]]; then
  # shellcheck disable=SC2086
  job=$(sbatch --parsable --export=ALL --chdir="$parts" $sbatch_args "$here/prepare.sbatch")
  # A failed prepare cancels the array (kill-on-invalid-dep); the merge then names the
  # missing shards, and the prepare job's log says why.
  after=(--dependency=afterok:"${job%%;*}" --kill-on-invalid-dep=yes)
fi
# shellcheck disable=SC2086
array=$(sbatch --parsable --export=ALL --chdir="$parts" --array=0-$((n - 1)) "${after[@]}" $sbatch_args \
  "$here/shard.sbatch")
array=${array%%;*}
# shellcheck disable=SC2086
merge=$(sbatch --parsable --export=ALL --chdir="$parts" --dependency=afterany:"$array" $sbatch_args "$here/merge.sbatch")
echo "$array ${merge%%;*}"
