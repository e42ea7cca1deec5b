#!/usr/bin/env bash
# Every command the README and docs/*.md show in a ```sh block runs as written, from a
# folder laid out like a fresh clone (scenes/, tools/, tests/, and build/ holding the
# binary under test), each block as one script with `set -e`, so that a user who copies
# it gets what the page promises. A few lines cannot run here; they are replaced by a
# no-op and listed with the reason:
#   tools/demo.sh, tools/test.sh   the set-up itself: CI runs tools/test.sh, and both
#                                  install packages and build in the checkout
#   tools/slurm/...                need a Slurm cluster; ctest `slurm` runs these scripts
#                                  on a single-node Slurm
# Usage: test_doc_commands.sh VKRAYCAST SOURCE_DIR
set -uo pipefail
bin=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=../check.sh
source "$src/tests/check.sh"

clone=$work/clone
mkdir -p "$clone"
for d in scenes tools tests; do ln -s "$src/$d" "$clone/$d"; done
ln -s "$(dirname "$(realpath "$bin")")" "$clone/build"

skipped=()
# The ```sh blocks of a page, each written to $work/blocks/PAGE-LINE.sh.
mkdir -p "$work/blocks"
for page in "$src/README.md" "$src"/docs/*.md; do
  awk -v out="$work/blocks" -v name="$(basename "$page" .md)" '
    /^```sh[[:space:]]*$/ { inside = 1; file = sprintf("%s/%s-%04d.sh", out, name, NR + 1); printf "" > file; next }
    /^```/ && inside { inside = 0; close(file); next }
    inside { print > file }' "$page"
done

blocks=0
for block in "$work"/blocks/*.sh; do
  [[ -e $block ]] || continue
  name=$(basename "$block" .sh)
  script=$work/run-$name.sh
  { echo "set -euo pipefail"; cat "$block"; } >"$script"
  # Lines that cannot run here become no-ops, remembered with their page.
  while IFS= read -r line; do skipped+=("$name: $line"); done < <(grep -E '^[[:space:]]*tools/(demo|test)\.sh|^[[:space:]]*tools/slurm/' "$block")
  sed -i -E 's@^([[:space:]]*)(tools/(demo|test)\.sh|tools/slurm/).*@\1: skipped@' "$script"
  grep -qvE '^[[:space:]]*(set -euo pipefail|: skipped|#.*)?[[:space:]]*$' "$script" || continue
  blocks=$((blocks + 1))
  (cd "$clone" && timeout 600 bash "$script") >"$work/$name.out" 2>"$work/$name.err"
  st=$?
  check "$name (commands as written)" "$([[ $st == 0 ]] && echo ok || echo "exit $st: $(tail -5 "$work/$name.err")")"
done
check "blocks found" "$([[ $blocks -ge 4 ]] && echo ok || echo "only $blocks blocks with commands")"
# The README's compare example passes, and says so.
grep -q '^PASS' "$work"/README-*.out && check "the README's compare example passes" ok ||
  check "the README's compare example passes" "no PASS in its output"
echo "not run here (see the header for why):"
printf '  %s\n' "${skipped[@]}"
finish
