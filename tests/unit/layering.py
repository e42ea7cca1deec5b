#!/usr/bin/env python3
"""The host's folders are the stages of the data flow (docs/design.md, "Source layout"),
and each stage may include only itself and the stages below it; no file may reach itself
through its includes. Fails naming the file and the include that breaks the rule.
Usage: layering.py REPO_ROOT"""
import os
import re
import sys

root = sys.argv[1]
host = os.path.join(root, "host")
# Stage -> the stages its files may include. Includes with no folder (rc_shared.h, the
# generated SPIR-V and version headers) are the shader's shared header or build outputs.
allowed = {
    "math": {"math"},
    "base": {"base", "math"},
    "image": {"image"},
    "scene": {"scene", "base", "math"},
    "ref": {"ref", "scene", "base", "math"},
    "gpu": {"gpu", "scene", "base", "math"},
    "compare": {"compare", "base", "math"},
    "cli": {"cli", "compare", "gpu", "ref", "scene", "image", "base", "math"},
}
include = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
graph, problems = {}, []
for stage in sorted(os.listdir(host)):
    folder = os.path.join(host, stage)
    if not os.path.isdir(folder):
        problems.append(f"host/{stage}: a file outside the stage folders")
        continue
    if stage not in allowed:
        problems.append(f"host/{stage}/: a folder that is not a stage of tests/unit/layering.py")
        continue
    for name in sorted(os.listdir(folder)):
        rel = f"{stage}/{name}"
        with open(os.path.join(folder, name), encoding="utf-8") as f:
            targets = include.findall(f.read())
        graph[rel] = [t for t in targets if "/" in t]
        for t in targets:
            if "/" not in t:
                continue
            to = t.split("/")[0]
            if to not in allowed[stage]:
                problems.append(f"host/{rel}: includes {t}: stage {stage} may include only {sorted(allowed[stage])}")
            elif not os.path.exists(os.path.join(host, t)):
                problems.append(f"host/{rel}: includes {t}, which does not exist")

# No include cycles (depth-first search; a grey node reached again closes a cycle).
state = {}
def visit(node, trail):
    state[node] = "grey"
    for t in graph.get(node, []):
        if state.get(t) == "grey":
            problems.append("include cycle: " + " -> ".join(trail[trail.index(t):] + [t]))
        elif t not in state:
            visit(t, trail + [t])
    state[node] = "black"
for node in sorted(graph):
    if node not in state:
        visit(node, [node])

for p in problems:
    print("FAIL:", p)
stages = sorted({k.split("/")[0] for k in graph})
print(f"layering: {len(graph)} files in {len(stages)} stages ({', '.join(stages)}), "
      f"{sum(len(v) for v in graph.values())} includes checked, {len(problems)} problems")
sys.exit(1 if problems else 0)
