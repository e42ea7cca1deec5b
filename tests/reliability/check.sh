# Sourced by the reliability tests. `check NAME RESULT` counts RESULT "ok" as a pass and
# anything else as a failure, printed with NAME and the reason; `finish` prints the
# closing "N passed, N failed" line and fails when anything failed.
failed=0 passed=0
check() {
  if [[ "$2" == ok ]]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: $1: $2"; fi
}
finish() {
  echo "$passed passed, $failed failed"
  ((failed == 0))
}
