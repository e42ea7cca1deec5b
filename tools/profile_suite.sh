#!/usr/bin/env bash
# Where the test suite's time goes: runs ctest in BUILD (default build/) with
# BUILD/vkraycast wrapped by a script that logs each process's CPU time (user + system,
# its children included), wall time, exit status, subcommand and the ctest test that
# started it, then prints the totals by test and by subcommand. COLD=1 first moves the
# tests' Mesa shader cache and specialized-module cache aside (restored at the end), as a
# clean clone has them, and counts the shaders the run compiled (the entries of Mesa's
# cache). The wrapper is removed and the binary restored on exit, even on Ctrl-C.
# Left out, because they look at the binary itself (its exit on a signal, its file, the
# libraries it loads) and fail or wait for their timeout behind a wrapper: cli, writers,
# commit, faults, exr_writer (its ulimit -f binds the wrapper's log too). Extra arguments go to ctest (e.g. -R certified).
# Usage: tools/profile_suite.sh [BUILD] [CTEST ARGS...]   (log: BUILD/profile-suite.log)
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(cd "${1:-build}" && pwd)
shift $(($# > 0 ? 1 : 0))
bin=$build/vkraycast log=$build/profile-suite.log
[[ -x $bin && ! -e $bin.real ]] || { echo "profile_suite: no $bin, or $bin.real is left from a run: restore it first" >&2; exit 2; }
export VK_DRIVER_FILES=${VK_DRIVER_FILES:-/usr/share/vulkan/icd.d/lvp_icd.x86_64.json} XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
restore() {
  [[ -e $bin.real ]] && mv -f "$bin.real" "$bin"
  if [[ ${COLD:-0} == 1 ]]; then
    for d in mesa-shader-cache cache; do
      [[ -d $build/$d.profile-saved ]] && rm -rf "${build:?}/$d" && mv "$build/$d.profile-saved" "$build/$d"
    done
  fi
  return 0
}
trap restore EXIT
if [[ ${COLD:-0} == 1 ]]; then
  for d in mesa-shader-cache cache; do [[ -d $build/$d ]] && mv "$build/$d" "$build/$d.profile-saved"; done
fi
mv "$bin" "$bin.real"
cat >"$bin" <<EOF
#!/bin/bash
# Written by tools/profile_suite.sh for the length of one run.
test=?
p=\$\$
while [[ \$p -gt 1 ]]; do
  pp=\$(awk '{print \$4}' /proc/\$p/stat 2>/dev/null) || break
  if [[ \$(cat /proc/\$pp/comm 2>/dev/null) == ctest ]]; then test=\$(tr '\\0' ' ' </proc/\$p/cmdline | cut -c1-300); break; fi
  p=\$pp
done
t0=\$(date +%s%N)
"$bin.real" "\$@"
rc=\$?
t1=\$(date +%s%N)
times >"$build/.times.\$\$"
read -r cpu < <(tail -1 "$build/.times.\$\$" | tr 'ms' '  ' | awk '{print \$1 * 60 + \$2 + \$3 * 60 + \$4}')
rm -f "$build/.times.\$\$"
echo "\$cpu \$(( (t1 - t0) / 1000000 )) \$rc \${1:-none} [\$test]" >>"$log"
exit \$rc
EOF
chmod +x "$bin"
: >"$log"
(cd "$build" && ctest -j"$(($(nproc) + 1))" --timeout 900 -E '^(cli|writers|commit|faults|exr_writer)$' "$@") || echo "(some tests failed: see above)"
python3 - "$log" "$build" "${COLD:-0}" <<'PY'
import collections, os, re, sys
log, build, cold = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
by_test, by_cmd = collections.defaultdict(lambda: [0, 0.0]), collections.defaultdict(lambda: [0, 0.0])
for line in open(log):
    m = re.match(r"(\S+) (\d+) (\d+) (\S+) \[(.*)\]", line)
    if not m:
        continue
    cpu, test = float(m[1]), m[5]
    name = re.search(r"(test_\w+\.sh|gpu_vs_cpu\.sh|extremes/run\.sh|bad_input/run\.sh|tests/test_\w+|\w+\.py)", test)
    name = name[1] if name else test[:60]
    for table, key in ((by_test, name), (by_cmd, m[4])):
        table[key][0] += 1
        table[key][1] += cpu
procs = sum(n for n, _ in by_cmd.values())
print(f"\n{procs} vkraycast processes, {sum(c for _, c in by_cmd.values()):.0f} s of CPU (user + system)")
print("\n| test (its script) | processes | CPU s | CPU s a process |\n|---|---|---|---|")
for k, (n, c) in sorted(by_test.items(), key=lambda kv: -kv[1][1]):
    print(f"| {k} | {n} | {c:.1f} | {c / n:.2f} |")
print("\n| subcommand | processes | CPU s | CPU s a process |\n|---|---|---|---|")
for k, (n, c) in sorted(by_cmd.items(), key=lambda kv: -kv[1][1]):
    print(f"| {k} | {n} | {c:.1f} | {c / n:.2f} |")
if cold:
    entries = sum(1 for _, _, fs in os.walk(os.path.join(build, "mesa-shader-cache")) for f in fs if f != "index")
    print(f"\nMesa's shader cache, empty at the start, holds {entries} entries: one per shader compiled")
PY
