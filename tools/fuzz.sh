#!/usr/bin/env bash
# Fuzzes the input parsers with libFuzzer (clang), ASan and UBSan: the JSON scene parser
# and the Bezier patch-file reader, which share a slot, the CSE167 .test parser and the
# prepared-scene (.vkrs) reader, which share another, and mesh loading, each slot for FUZZ_SECONDS (60) from the seed corpus in tests/fuzz/corpus/. Prints the executions per target; exits 1 on
# any crash, hang (10 s an input), leak or sanitizer report, leaving the input in
# build-fuzz/findings/. The three run side by side: -max_total_time is wall time, so each
# gets FUZZ_SECONDS x cores / 3 of wall time, which is FUZZ_SECONDS of CPU time apiece
# on a machine with fewer than three cores (the same fuzzing as one after another, in
# less wall time). Mesh loading runs assimp in a process of its own (host/scene/
# mesh_wire.h), given 3 s here (VKRAYCAST_MESH_TIMEOUT_S), well inside the 10 s that make
# an input a finding; what assimp does there is an error message, not a finding. On a
# failure the end of the log and each finding (base64) are printed, so that a CI log
# alone reproduces it.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKRAYCAST_FUZZ=ON >&2
fi
cmake --build build-fuzz --target fuzz_json fuzz_test fuzz_mesh fuzz_prepared fuzz_patch -j"$(nproc)" >&2
mkdir -p build-fuzz/findings
cores=$(nproc)
wall=$(( cores >= 3 ? seconds : (seconds * 3 + cores - 1) / cores ))
targets=(json test mesh)
fuzz() { # TARGET CORPUS SECONDS [ENV...]: one libFuzzer run, its log appended to the target's
  local target=$1 corpus=build-fuzz/corpus-$2 seconds=$3
  shift 3
  mkdir -p "$corpus"
  cp -n tests/fuzz/corpus/$target/* "$corpus"/ 2>/dev/null || true
  env ASAN_OPTIONS=fast_unwind_on_malloc=1 VKRAYCAST_MESH_TIMEOUT_S=3 "$@" build-fuzz/fuzz_$target "$corpus" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -close_fd_mask=2 -artifact_prefix=build-fuzz/findings/$target- >>"build-fuzz/fuzz-$target.log" 2>&1
}
run_one() {
  local target=$1
  : >"build-fuzz/fuzz-$target.log"
  if [[ $target == mesh ]]; then
    # Each mesh input starts the importer process (about 20 ms), so two thirds of the
    # slot go to this process's own code with the importer replaced by /bin/false (every
    # import then fails at once: the checks before it and the error path, ~30x the
    # executions), and the rest to the real importer (its answers and the triangles),
    # from a corpus of its own: libFuzzer first runs every input of its corpus, and the
    # first run's hundreds would take that third through the importer.
    fuzz mesh mesh $((wall * 2 / 3)) VKRAYCAST_MESH_IMPORTER=/bin/false || return 1
    fuzz mesh mesh-import $((wall - wall * 2 / 3))
  elif [[ $target == json ]]; then
    # A quarter of the JSON slot goes to the Bezier patch files (their own log and findings).
    : >"build-fuzz/fuzz-patch.log"
    rm -f build-fuzz/failed-in-json-slot
    fuzz json json $((wall - wall / 4)) || return 1
    fuzz patch patch $((wall / 4)) || { echo patch >build-fuzz/failed-in-json-slot; return 1; }
  elif [[ $target == test ]]; then
    # The .test parser has run over a million inputs a CI run for a long while; half its
    # slot goes to the prepared-scene reader (its own log and findings).
    : >"build-fuzz/fuzz-prepared.log"
    rm -f build-fuzz/failed-in-slot
    fuzz test test $((wall / 2)) || return 1
    fuzz prepared prepared $((wall - wall / 2)) || { echo prepared >build-fuzz/failed-in-slot; return 1; }
  else
    fuzz "$target" "$target" "$wall"
  fi
}
declare -A pid
for target in "${targets[@]}"; do
  run_one "$target" &
  pid[$target]=$!
done
failed=0
# report NAME RESULT: the slot's (or its second target's) executions, corpus and result;
# on a failure the end of its log and its findings in base64.
report() {
  local name=$1 result=$2 log=build-fuzz/fuzz-$1.log
  if [[ $result != ok ]]; then
    echo "--- the end of $log:"
    tail -n 60 "$log"
    for finding in build-fuzz/findings/"$name"-*; do
      [[ -f $finding ]] || continue
      echo "--- $finding ($(stat -c %s "$finding") bytes), base64:"
      head -c 65536 "$finding" | base64 -w 100
    done
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | awk '{ n += $1 } END { print n }')
  echo "fuzz $name: ${runs:-?} executions in its share of ${wall} s of wall time beside the other slots, corpus $(ls "build-fuzz/corpus-$name" 2>/dev/null | wc -l) inputs: $result"
}
for target in "${targets[@]}"; do
  result=ok
  if ! wait "${pid[$target]}"; then
    result="FAILED (the log and findings above)"
    failed=1
  fi
  if [[ $target == test ]]; then
    # The slot's second run failed where it left its name.
    pr=ok
    if [[ $result != ok && -f build-fuzz/failed-in-slot ]]; then pr=$result result=ok; fi
    report test "$result"
    report prepared "$pr"
  elif [[ $target == json ]]; then
    pr=ok
    if [[ $result != ok && -f build-fuzz/failed-in-json-slot ]]; then pr=$result result=ok; fi
    report json "$result"
    report patch "$pr"
  else
    report "$target" "$result"
  fi
done
exit $failed
