#!/usr/bin/env bash
# A commit that fails halfway rolls back (issue 45, class 2), by fault injection at every
# step, as SQLite's I/O-error tests do: the rename of the image (step 0), of the AOV file
# (1) and of the statistics (2) fails in turn (VKRAYCAST_FAULT=commit:STEP). With old
# files in place, all three must come out byte for byte as they were; with none, none
# may exist after; exit status 2 and no backup or temporary left either way. And a
# SIGTERM sent while a commit is held between two renames (commit-pause:STEP) must wait
# for it: the process then dies by the signal with all three files new.
# Usage: test_commit.sh VKRAYCAST SCENES_DIR WORKDIR
set -uo pipefail
bin=$1 scenes=$2 work=$3
rm -rf "$work" && mkdir -p "$work/out" "$work/old"
source "$(dirname "$0")/../check.sh"
S=$scenes/shadows.json
render() { # SIZE [env...]: the run's three outputs into $work/out
  local size=$1
  shift
  env "$@" "$bin" render "$S" -o "$work/out/i.png" --aov "$work/out/i.aov.exr" --stats-json "$work/out/s.json" \
    --width "$size" --height "$size" --quiet 2>"$work/err"
}
leftovers() { find "$work/out" -name '.*' -o -name '*vkraycast*' | head -3; }
render 24 || check "old files" "exit $?: $(cat "$work/err")"
cp "$work/out"/* "$work/old/"

for step in 0 1 2; do
  render 32 VKRAYCAST_FAULT=commit:$step
  got=$? why=ok
  [[ $got == 2 ]] || why="exit status $got, expected 2"
  grep -q "injected fault" "$work/err" || why="$why; stderr: $(head -c 200 "$work/err")"
  for f in i.png i.aov.exr s.json; do cmp -s "$work/old/$f" "$work/out/$f" || why="$why; $f is not the old one"; done
  [[ -z $(leftovers) ]] || why="$why; left behind: $(leftovers)"
  check "rename $step fails with old files: all three old" "$why"

  rm -f "$work/out"/*
  render 32 VKRAYCAST_FAULT=commit:$step
  got=$? why=ok
  [[ $got == 2 ]] || why="exit status $got, expected 2"
  [[ -z $(ls -A "$work/out") ]] || why="$why; files exist: $(ls -A "$work/out")"
  check "rename $step fails with no old files: none written" "$why"
  cp "$work/old"/* "$work/out/"
done

# The same render without a fault replaces all three (the injection is what failed).
render 32
check "without a fault all three are new" \
  "$([[ $? == 0 ]] && ! cmp -s "$work/old/i.png" "$work/out/i.png" && ! cmp -s "$work/old/s.json" "$work/out/s.json" &&
     [[ -z $(leftovers) ]] && echo ok || echo "exit or files: $(cat "$work/err")")"

# A signal during the commit waits for its end.
for step in 0 1; do
  cp "$work/old"/* "$work/out/"
  # exec: the signal must reach vkraycast itself, not a subshell around it.
  (exec env VKRAYCAST_FAULT=commit-pause:$step "$bin" render "$S" -o "$work/out/i.png" --aov "$work/out/i.aov.exr" \
    --stats-json "$work/out/s.json" --width 32 --height 32 --quiet 2>"$work/err") &
  pid=$!
  # The pause begins once the step's rename is done: wait for its file to change.
  f=i.png
  [[ $step == 1 ]] && f=i.aov.exr
  for _ in $(seq 1 300); do cmp -s "$work/old/$f" "$work/out/$f" || break; sleep 0.05; done
  kill -TERM "$pid"
  wait "$pid"
  got=$? why=ok
  [[ $got == 143 ]] || why="exit status $got, expected 143 (SIGTERM)"
  for g in i.png i.aov.exr s.json; do ! cmp -s "$work/old/$g" "$work/out/$g" || why="$why; $g is still the old one"; done
  [[ -z $(leftovers) ]] || why="$why; left behind: $(leftovers)"
  check "SIGTERM after rename $step: the commit ends, then the signal" "$why"
done
finish
