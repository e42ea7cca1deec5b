#!/usr/bin/env bash
# The CPU reference mirrors the shader file by file and function by function
# (docs/design.md §3): for each shaders/rc_X.glsl, host/ref/ref_X.c defines the same functions, in the
# same order, named ref_NAME or REF(NAME). GPU-only includes (the loop budget, scene
# buffer access, precision macros) have no twin. Usage: check_mirror.sh REPO_ROOT
set -euo pipefail
root=$1
gpu_only="rc_budget rc_scene_access rc_real"
glsl_functions() { sed -nE 's/^[a-z][a-z_0-9]* ([a-z_0-9]+)\(.*/\1/p' "$1"; }
c_functions() {
  grep -vE '^static ' "$1" | sed -nE -e 's/^[a-z][a-z_0-9 *]* REF\(([a-z_0-9]+)\)\(.*/\1/p' \
    -e 's/^[a-z][a-z_0-9 *]* ref_([a-z_0-9]+)\(.*/\1/p'
}
failed=0 pairs=0 functions=0
for glsl in "$root"/shaders/rc_*.glsl; do
  base=$(basename "$glsl" .glsl)
  [[ " $gpu_only " == *" $base "* ]] && continue
  ref=$root/host/ref/ref_${base#rc_}.c
  if [[ ! -f "$ref" ]]; then
    echo "FAIL: $base.glsl has no CPU twin host/ref/$(basename "$ref")"
    failed=1
    continue
  fi
  if ! diff -u <(glsl_functions "$glsl") <(c_functions "$ref") >/tmp/mirror.$$; then
    echo "FAIL: functions of shaders/$base.glsl (-) and host/ref/$(basename "$ref") (+) differ:"
    sed 1,2d /tmp/mirror.$$
    failed=1
  fi
  pairs=$((pairs + 1))
  functions=$((functions + $(glsl_functions "$glsl" | wc -l)))
done
rm -f /tmp/mirror.$$
echo "mirror: $pairs shader includes, $functions functions, each with its ref_ twin in order"
exit $failed
