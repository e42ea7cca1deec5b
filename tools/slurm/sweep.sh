#!/usr/bin/env bash
# The speed-against-accuracy study (tools/tradeoff.sh: scenes x variants x spp, 252
# points) as one Slurm job array, a task per point, and a job that gathers the points into
# OUTDIR/accuracy.csv, the table and the plot once they are done (docs/cluster.md).
#   tools/slurm/sweep.sh [-a "SBATCH OPTIONS"] WORKDIR [OUTDIR]
# WORKDIR must lie on a filesystem every node sees (the references are rendered there
# once and shared). Points that fail are named by the gather job with the --array list
# that renders them again (then run the gather again: TRADEOFF_GATHER=1 TRADEOFF_WORK=
# WORKDIR tools/tradeoff.sh OUTDIR). Times compare only between points run on one kind of
# node: pin the array to one (--constraint, --nodelist) for the plot's time axis.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
sbatch_args=
while getopts "a:" o; do
  case $o in
    a) sbatch_args=$OPTARG ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
(($# >= 1)) || { sed -n '2,11p' "$0" >&2; exit 2; }
work=$(realpath -m "$1") out=$(realpath -m "${2:-$here/../../docs}")
mkdir -p "$work"
points=$(TRADEOFF_COUNT=1 "$here/../tradeoff.sh")
export TRADEOFF_WORK=$work VKRAYCAST=${VKRAYCAST:-$(realpath "$here/../../build/vkraycast")}
# shellcheck disable=SC2086
array=$(sbatch --parsable --export=ALL --chdir="$work" --job-name=vkraycast-sweep --cpus-per-task=1 \
  --output=%x-%A_%a.log --array=0-$((points - 1)) $sbatch_args \
  --wrap "TRADEOFF_POINT=\$SLURM_ARRAY_TASK_ID $(printf %q "$here/../tradeoff.sh")")
array=${array%%;*}
# shellcheck disable=SC2086
gather=$(sbatch --parsable --export=ALL --chdir="$work" --job-name=vkraycast-gather --output=%x-%j.log \
  --dependency=afterany:"$array" $sbatch_args \
  --wrap "TRADEOFF_GATHER=1 $(printf %q "$here/../tradeoff.sh") $(printf %q "$out")")
echo "$array ${gather%%;*}"
