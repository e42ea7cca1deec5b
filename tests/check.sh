# Sourced by the shell tests of every folder (reliability/, cluster/, cli/, portability/,
# rescale/), as rc_test.h serves the C tests. `check NAME RESULT` counts RESULT "ok" as a pass and
# anything else as a failure, printed with NAME and the reason; `finish` prints the
# closing "N passed, N failed" line and fails when anything failed.
failed=0 passed=0
check() {
  if [[ "$2" == ok ]]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: $1: $2"; fi
}
# `because TEXT` adds TEXT to the caller's reason `why`, which is "ok" until the first.
because() { if [[ $why == ok ]]; then why=$1; else why="$why; $1"; fi; }
# `json_num FIELD FILE`, `json_str FIELD FILE`: a field of a --stats-json file.
json_num() { sed -n "s/.*\"$1\":[[:space:]]*\([-0-9.e+]*\).*/\1/p" "$2" | head -1; }
json_str() { sed -n "s/.*\"$1\":[[:space:]]*\"\([^\"]*\)\".*/\1/p" "$2" | head -1; }
# `expect_exit2 NAME OUT MESSAGE COMMAND...`: COMMAND must end within 60 s with exit
# status 2, MESSAGE on stderr and no file OUT.
expect_exit2() {
  local name=$1 out=$2 want=$3
  shift 3
  rm -f "$out"
  timeout 60 "$@" 2>"$work/err"
  local got=$? why=ok
  [[ $got == 2 ]] || because "exit status $got, expected 2"
  grep -qF -- "$want" "$work/err" || because "stderr: $(head -c 300 "$work/err"); expected: $want"
  [[ ! -e $out ]] || because "an image was written"
  check "$name" "$why"
}
# `expect_refusal NAME SCENE MESSAGE [render args...]`: rendering SCENE (with $bin into
# $work/o.png) must be refused so.
expect_refusal() {
  local name=$1 scene=$2 want=$3
  shift 3
  expect_exit2 "$name" "$work/o.png" "$want" "$bin" render "$scene" -o "$work/o.png" --quiet "$@"
}
# `same_pixels A B`: the two images' pixels equal bit for bit, by $bin's compare: no
# channel (AOV channels included) differs by more than 0.
same_pixels() { "$bin" compare "$1" "$2" --fail 0 --hardfail 0 >/dev/null 2>&1; }
# `loads_oiio COMMAND...`: how often COMMAND loads OpenImageIO's library (0: never).
loads_oiio() { LD_DEBUG=files "$@" 2>&1 >/dev/null | grep -cE 'file=(/[^ ]*/)?libOpenImageIO\.so' || true; }
finish() {
  echo "$passed passed, $failed failed"
  ((failed == 0))
}
