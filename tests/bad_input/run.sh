#!/usr/bin/env bash
# Table-driven bad-input test: each row of cases.txt runs vkraycast and asserts the exit
# status, a fixed string on stderr, and that no output file (nor a temporary) is left
# behind unless the command succeeded. Usage: run.sh VKRAYCAST DIR
set -uo pipefail
bin=$1 dir=$2
S=$dir/scenes
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0 passed=0 n=0
while IFS='|' read -r want expected args; do
  [[ -z "$want" || "$want" == \#* ]] && continue
  n=$((n + 1))
  OUT=$work/case$n.png
  eval "set -- $args"
  VKRAYCAST_MESH_TIMEOUT_S=3 "$bin" "$@" >"$work/stdout" 2>"$work/stderr" </dev/null
  got=$?
  problems=()
  [[ "$got" == "$want" ]] || problems+=("exit status $got, expected $want")
  if [[ -n "$expected" ]] && ! grep -qF -- "$expected" "$work/stderr"; then
    problems+=("stderr lacks: $expected")
  fi
  if [[ "$want" != 0 ]]; then
    leftovers=$(find "$work" -name "*case$n*")
    [[ -z "$leftovers" ]] || problems+=("output left behind: $leftovers")
  else
    [[ -s "$OUT" ]] || problems+=("no output written")
  fi
  if ((${#problems[@]})); then
    failed=$((failed + 1))
    echo "FAIL: $args"
    printf '  %s\n' "${problems[@]}"
    sed 's/^/  stderr: /' "$work/stderr"
  else
    passed=$((passed + 1))
  fi
done <"$dir/cases.txt"
echo "$passed passed, $failed failed"
((failed == 0 && passed > 0))
