#!/usr/bin/env bash
# The speed-against-accuracy study (tools/tradeoff.sh: scenes x variants x spp, 252
# points) as one Slurm job array, a task per point (`vkraycast tradeoff --point I`), and
# a job that gathers the points into WORKDIR/tradeoff.csv, the summary and the plot once
# they are done (`--gather`; docs/cluster.md).
#   tools/slurm/sweep.sh [-a "SBATCH OPTIONS"] WORKDIR
# WORKDIR must lie on a filesystem every node sees (the references are rendered there
# once and shared). A point that is missing is named by the gather job, with the --point
# that measures it again (then gather again: tools/tradeoff.sh WORKDIR --gather). Times
# compare only between points run on one kind of node: pin the array to one
# (--constraint, --nodelist) for the plot's time axis.
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
(($# >= 1)) || { sed -n '2,12p' "$0" >&2; exit 2; }
work=$(realpath -m "$1")
mkdir -p "$work"
points=$("$here/../tradeoff.sh" "$work" --points)
export VKRAYCAST=${VKRAYCAST:-$(realpath "$here/../../build/vkraycast")}
# shellcheck disable=SC2086
array=$(sbatch --parsable --export=ALL --chdir="$work" --job-name=vkraycast-sweep --cpus-per-task=1 \
  --output=%x-%A_%a.log --array=0-$((points - 1)) $sbatch_args \
  --wrap "$(printf %q "$here/../tradeoff.sh") $(printf %q "$work") --point \$SLURM_ARRAY_TASK_ID --quiet")
array=${array%%;*}
# shellcheck disable=SC2086
gather=$(sbatch --parsable --export=ALL --chdir="$work" --job-name=vkraycast-gather --output=%x-%j.log \
  --dependency=afterany:"$array" $sbatch_args \
  --wrap "$(printf %q "$here/../tradeoff.sh") $(printf %q "$work") --gather")
echo "$array ${gather%%;*}"
