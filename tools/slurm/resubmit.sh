#!/usr/bin/env bash
# Renders shard I of a frame again (after `vkraycast merge` named it missing) and merges
# once it is done: sbatch --array=I with the settings submit.sh wrote to PARTS/job.env.
#   tools/slurm/resubmit.sh PARTS I
# Prints the shard's job ID and the merge job's ID.
set -euo pipefail
parts=$1 i=$2
# shellcheck source=/dev/null
source "$parts/job.env"
# shellcheck disable=SC2086
shard=$(sbatch --parsable --export=ALL --chdir="$parts" --array="$i" $VKRAYCAST_SBATCH_ARGS "$VKRAYCAST_SLURM_TOOLS/shard.sbatch")
shard=${shard%%;*}
# shellcheck disable=SC2086
merge=$(sbatch --parsable --export=ALL --chdir="$parts" --dependency=afterany:"$shard" $VKRAYCAST_SBATCH_ARGS \
  "$VKRAYCAST_SLURM_TOOLS/merge.sbatch")
echo "$shard ${merge%%;*}"
