#!/usr/bin/env python3
"""Every loop of the shader steps the lane's loop budget (shaders/rc_budget.glsl): llvmpipe
ends a loop silently past 65,535 iterations of a SIMD vector, the host sizes each dispatch
from the steps it plans (host/gpu/gpu_plan.c), and a loop outside that plan can be cut
where the plan says there is room. A cut loop is not an error anyone sees: a certificate's
loop cut short once certified eight lanes of the teapot with decisions other than f64's
(4c09838). So a loop must take its steps: budget_step() or budget_take() in its header or
in the first lines of its body, or budget_take() for the whole loop in the lines before it.
A loop that does not is listed in tests/unit/loop_budget_exceptions.txt with the reason its
iterations are few and bounded by work the plan counts. Fails naming each loop that is
neither, and each listed exception that no longer matches a loop.
Usage: loop_budget.py REPO_ROOT"""
import os
import re
import sys

root = sys.argv[1]
shaders = os.path.join(root, "shaders")
listing = os.path.join(root, "tests", "unit", "loop_budget_exceptions.txt")
loop = re.compile(r"\b(for|while)\s*\(")
budget = re.compile(r"\bbudget_(step|take)\s*\(|\bbudget_steps\b")
before = re.compile(r"\bbudget_take\s*\(")
BODY_LINES, BEFORE_LINES = 4, 12

# The exceptions: "file: the loop's first line, stripped  # why" per entry.
exceptions = {}
for number, line in enumerate(open(listing), 1):
    text = line.strip()
    if not text or text.startswith("#"):
        continue
    head, _, why = text.partition("  # ")
    name, _, code = head.partition(": ")
    if not why.strip() or not code:
        sys.exit(f"{listing}:{number}: an entry is 'file: loop line  # why', with a reason")
    exceptions[(name, code.strip())] = False

problems = []
loops = 0
for name in sorted(os.listdir(shaders)):
    if not name.endswith((".glsl", ".comp")):
        continue
    lines = open(os.path.join(shaders, name)).read().split("\n")
    for i, line in enumerate(lines):
        code = line.split("//")[0]
        if not loop.search(code):
            continue
        loops += 1
        if budget.search("\n".join(l.split("//")[0] for l in lines[i:i + 1 + BODY_LINES])):
            continue
        if before.search("\n".join(l.split("//")[0] for l in lines[max(0, i - BEFORE_LINES):i])):
            continue
        key = (name, line.strip())
        if key in exceptions:
            exceptions[key] = True
            continue
        problems.append(f"shaders/{name}:{i + 1}: a loop that takes no budget steps: {line.strip()}")

for (name, code), seen in exceptions.items():
    if not seen:
        problems.append(f"{listing}: '{name}: {code}' matches no unbudgeted loop; remove it")

for p in problems:
    print(p)
print(f"loop budget: {loops} loops in shaders/, {len(exceptions)} listed exceptions, {len(problems)} problems")
sys.exit(1 if problems else 0)
