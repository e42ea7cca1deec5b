#!/usr/bin/env bash
# Fuzzes the input parsers with libFuzzer (clang), ASan and UBSan: the JSON scene parser,
# the CSE167 .test parser and mesh loading through assimp, each for FUZZ_SECONDS (60) from
# the seed corpus in tests/fuzz/corpus/. Prints the executions per target; exits 1 on
# any crash, hang (10 s an input), leak or sanitizer report, leaving the input in
# build-fuzz/findings/. The three run side by side: -max_total_time is wall time, so each
# gets FUZZ_SECONDS x cores / 3 of wall time, which is FUZZ_SECONDS of CPU time apiece
# on a machine with fewer than three cores (the same fuzzing as one after another, in
# less wall time).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKRAYCAST_FUZZ=ON >&2
fi
cmake --build build-fuzz --target fuzz_json fuzz_test fuzz_mesh -j"$(nproc)" >&2
mkdir -p build-fuzz/findings
export LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp
cores=$(nproc)
wall=$(( cores >= 3 ? seconds : (seconds * 3 + cores - 1) / cores ))
targets=(json test mesh)
run_one() {
  local target=$1 corpus=build-fuzz/corpus-$1
  mkdir -p "$corpus"
  cp -n tests/fuzz/corpus/$target/* "$corpus"/ 2>/dev/null || true
  # Mesh loading goes through assimp (C++): full (DWARF) allocation stacks there, since
  # libstdc++ has no frame pointers, the fast unwinder stops at operator new, and a leak
  # inside assimp would not show the libassimp frame that lsan.supp names (seen: 4,928
  # bytes from a malformed STL). The C parsers keep the fast unwinder (50x the executions).
  local unwind=1
  [[ $target == mesh ]] && unwind=0
  ASAN_OPTIONS=fast_unwind_on_malloc=$unwind VKRAYCAST_MESH_TIMEOUT_S=3 build-fuzz/fuzz_$target "$corpus" -max_total_time="$wall" -timeout=10 \
    -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -close_fd_mask=2 \
    -artifact_prefix=build-fuzz/findings/$target- >"build-fuzz/fuzz-$target.log" 2>&1
}
declare -A pid
for target in "${targets[@]}"; do
  run_one "$target" &
  pid[$target]=$!
done
failed=0
for target in "${targets[@]}"; do
  log=build-fuzz/fuzz-$target.log
  if wait "${pid[$target]}"; then
    result=ok
  else
    result="FAILED (see $log and build-fuzz/findings/)"
    failed=1
    echo "--- the end of $log:"
    tail -n 60 "$log"
    for finding in build-fuzz/findings/"$target"-*; do
      [[ -f $finding ]] || continue
      echo "--- $finding ($(stat -c %s "$finding") bytes), base64:"
      head -c 65536 "$finding" | base64 -w 100
    done
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  echo "fuzz $target: ${runs:-?} executions in ${wall} s of wall time beside the other two, corpus $(ls "build-fuzz/corpus-$target" | wc -l) inputs: $result"
done
exit $failed
