#!/usr/bin/env python3
"""Where lavapipe's JIT code spends a render's time, by function and by loop.

Debian's Mesa 22.3 is a release build: GALLIVM_DEBUG=perf/ir/asm print nothing and write
no perf map, so `perf report` lumps the shader into one anonymous region. This tool runs
the render under `perf record`, copies the process's anonymous executable mappings (the
JIT code) out of /proc/PID/mem while it runs, disassembles them with objdump, and then
attributes each sample to an instruction: per function (llvmpipe emits each texel-buffer
fetch as an out-of-line helper, the shader as one function) and per loop (backward
jumps) of the largest function, with the operations that name a loop's work (vsqrtps: a
sphere test; vdivps: triangle and box slopes; calls: texel fetches).

Usage: tools/profile_jit.py [--top N] [--annotate K] [--loop +OFFSET] -- vkraycast render SCENE -o OUT [options]
(run it with --repeat 4 or more so that the steady state outweighs start-up). --annotate K
prints the K-th hottest innermost loop (1 = hottest) instruction by instruction with its
samples: what finding 11 in docs/performance.md was read from. --loop +OFFSET prints the
loop the table lists at that offset from the shader function's start, inner loops included.
Needs perf (Debian linux-perf), objdump and permission to read the process's memory
(root, or ptrace_scope 0).
"""
import collections
import os
import re
import subprocess
import sys
import tempfile
import threading
import time


def dump_jit(pid, out_dir, dumps):
    """Copies anonymous executable mappings of pid until it exits; keeps the latest copy."""
    while True:
        try:
            maps = open(f"/proc/{pid}/maps").read().splitlines()
        except OSError:
            return
        for line in maps:
            parts = line.split()
            perm, path = parts[1], (parts[5] if len(parts) > 5 else "")
            if "x" not in perm or path:
                continue
            lo, hi = (int(x, 16) for x in parts[0].split("-"))
            try:
                with open(f"/proc/{pid}/mem", "rb") as mem:
                    mem.seek(lo)
                    data = mem.read(hi - lo)
            except OSError:
                continue
            name = os.path.join(out_dir, f"jit_{lo:x}.bin")
            with open(name, "wb") as f:
                f.write(data)
            dumps[lo] = (hi, name)
        time.sleep(0.2)


INSN = re.compile(r"\s*([0-9a-f]+):\s+(?:[0-9a-f]{2} )+\s*(.*)")
JUMP = re.compile(r"(j\w+)\s+0x([0-9a-f]+)")


def disassemble(lo, path):
    out = subprocess.run(["objdump", "-D", "-b", "binary", "-m", "i386:x86-64", f"--adjust-vma={lo:#x}", path],
                         check=True, capture_output=True, text=True).stdout
    insns = []
    for line in out.splitlines():
        m = INSN.match(line)
        if m and m.group(2).strip():
            insns.append((int(m.group(1), 16), m.group(2).strip()))
    return insns


def split_functions(insns):
    """Functions end at `ret`; padding between them joins the next one."""
    funcs, cur = [], []
    for a, text in insns:
        cur.append((a, text))
        if text.startswith("ret"):
            funcs.append(cur)
            cur = []
    if cur:
        funcs.append(cur)
    return funcs


def describe(insns):
    ops = collections.Counter()
    for _, text in insns:
        op = text.split()[0] if text else ""
        if op in ("vsqrtps", "vsqrtpd", "vdivps", "vdivpd", "call"):
            ops[op] += 1
    return " ".join(f"{n} {op}" for op, n in sorted(ops.items()))


def main():
    argv = sys.argv[1:]
    top, annotate, loop_at = 12, 0, None
    while argv[:1] in (["--top"], ["--annotate"], ["--loop"]):
        if argv[0] == "--top":
            top = int(argv[1])
        elif argv[0] == "--loop":
            loop_at = int(argv[1], 16)
        else:
            annotate = int(argv[1])
        argv = argv[2:]
    if argv[:1] == ["--"]:
        argv = argv[1:]
    if not argv:
        sys.exit(__doc__)
    work = tempfile.mkdtemp(prefix="profile_jit.")
    data = os.path.join(work, "perf.data")
    proc = subprocess.Popen(["perf", "record", "-q", "-e", "cpu-clock", "-F", "2000", "-o", data, "--"] + argv,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    # perf forks the command: find the child whose command line is ours.
    child = None
    while child is None and proc.poll() is None:
        for entry in os.listdir("/proc"):
            if entry.isdigit():
                try:
                    cmd = open(f"/proc/{entry}/cmdline").read().split("\0")
                except OSError:
                    continue
                if cmd[: len(argv)] == argv and int(entry) != proc.pid:
                    child = int(entry)
                    break
        time.sleep(0.01)
    dumps = {}
    watcher = threading.Thread(target=dump_jit, args=(child, work, dumps)) if child else None
    if watcher:
        watcher.start()
    err = proc.communicate()[1]
    if watcher:
        watcher.join()
    if proc.returncode != 0:
        sys.exit(f"profile_jit: the command failed (exit {proc.returncode}):\n{err}")
    ips, dso_of = collections.Counter(), {}
    script = subprocess.run(["perf", "script", "-i", data, "-F", "ip,dso"], capture_output=True, text=True).stdout
    for line in script.splitlines():
        fields = line.split()
        if fields:
            ip = int(fields[0], 16)
            ips[ip] += 1
            dso_of[ip] = os.path.basename(fields[1].strip("()")) if len(fields) > 1 else "?"
    total = sum(ips.values())
    regions = [(lo, hi, disassemble(lo, name)) for lo, (hi, name) in sorted(dumps.items())]
    elsewhere = collections.Counter()
    for ip, n in ips.items():
        if not any(lo <= ip < hi for lo, hi, _ in regions):
            elsewhere[dso_of[ip]] += n
    in_jit = total - sum(elsewhere.values())
    print(f"samples: {total}; in JIT code: {in_jit} ({100.0 * in_jit / max(total, 1):.1f} %), "
          f"{len(regions)} region(s), {sum(hi - lo for lo, hi, _ in regions)} bytes")
    # Outside the JIT code: the driver, the kernel, the host (BVH build, parsing, writing).
    print("elsewhere: " + ", ".join(f"{d} {100.0 * n / max(total, 1):.1f} %" for d, n in elsewhere.most_common(6)))
    funcs = []
    for _, _, insns in regions:
        for f in split_functions(insns):
            funcs.append((sum(ips.get(a, 0) for a, _ in f), f))
    funcs.sort(key=lambda x: -x[0])
    print("\nfunctions (a texel fetch helper is ~50 instructions ending in ret):")
    print("| start | instructions | samples | share | work |")
    print("|---|---|---|---|---|")
    for n, f in funcs[:top]:
        print(f"| {f[0][0]:#x} | {len(f)} | {n} | {100.0 * n / max(total, 1):.1f} % | {describe(f)} |")
    if not funcs:
        return
    body = max(funcs, key=lambda x: len(x[1]))[1]
    at = {a: i for i, (a, _) in enumerate(body)}
    loops = []
    for i, (a, text) in enumerate(body):
        m = JUMP.match(text)
        if m and int(m.group(2), 16) < a and int(m.group(2), 16) in at:
            j = at[int(m.group(2), 16)]
            loops.append((j, i))
    # Keep the widest loop for each head (a loop's several back edges), outermost first.
    widest = {}
    for j, i in loops:
        widest[j] = max(widest.get(j, i), i)
    loops = sorted(widest.items(), key=lambda x: (x[0], -x[1]))
    print(f"\nloops of the largest function ({len(body)} instructions), nested by indentation:")
    print("| loop | instructions | samples (without called helpers) | share | work |")
    print("|---|---|---|---|---|")
    stack = []
    for j, i in loops:
        while stack and not (stack[-1][0] <= j and i <= stack[-1][1]):
            stack.pop()
        n = sum(ips.get(a, 0) for a, _ in body[j : i + 1])
        if 100.0 * n / max(total, 1) >= 0.5:
            print(f"| {'. ' * len(stack)}+{body[j][0] - body[0][0]:#x}..+{body[i][0] - body[0][0]:#x} | {i - j + 1} | {n} | "
                  f"{100.0 * n / max(total, 1):.1f} % | {describe(body[j : i + 1])} |")
        stack.append((j, i))
    if loop_at is not None:
        # Offsets within the JIT region do not change between runs of the same shader; the
        # address does: a loop is named by its offset from the function's start.
        for j, i in loops:
            if body[j][0] - body[0][0] == loop_at:
                print(f"\nloop at +{loop_at:#x} ({body[j][0]:#x}..{body[i][0]:#x}):")
                for a, text in body[j : i + 1]:
                    print(f"{ips.get(a, 0):6d}  +{a - body[0][0]:#x}  {text}")
    if annotate:
        inner = [(j, i) for j, i in loops if not any(j <= j2 and i2 <= i and (j2, i2) != (j, i) for j2, i2 in loops)]
        inner.sort(key=lambda x: -sum(ips.get(a, 0) for a, _ in body[x[0] : x[1] + 1]))
        if annotate > len(inner):
            print(f"\n--annotate {annotate}: the shader has {len(inner)} innermost loops")
        else:
            j, i = inner[annotate - 1]
            print(f"\ninnermost loop {annotate} by samples, {body[j][0]:#x}..{body[i][0]:#x}:")
            for a, text in body[j : i + 1]:
                print(f"{ips.get(a, 0):6d}  {a:#x}  {text}")


if __name__ == "__main__":
    main()
