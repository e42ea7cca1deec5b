#!/usr/bin/env python3
"""Shader and reference bodies side by side: a prototype of the body comparison that issue 16
asks of the mirror check (docs/design.md §9). It is a report, not yet a test: today it
lists differences of spelling that its normalisation does not yet map (the C side's
pointer parameters and scene argument, the reference's rmax3 against the shader's nested
max, GLSL's `v / s` against the reference's `v * (1 / s)`, which is what llvmpipe lowers
the division to), beside any real divergence. tests/unit/check_mirror.sh is the gate
(names and order).

For each shaders/rc_X.glsl and host/ref/ref_X.c, bodies are compared after both are
reduced to what the arithmetic depends on:
- the operands, in order: every variable, field and constant as written, numbers by value
  (GLSL's 2.0 is C's 2); prefix calls (C's RV(sub)(a, b)) and infix operators (GLSL's a - b)
  keep their operands in the same order, so a swapped or missing operand shows;
- the operations, counted: + - * / and comparisons (C's RV(add), RV(scale), RV(neg) count
  as theirs), and the named functions (dot, sqrt, normalize, ...).
What differs only in spelling is mapped first (the tables below). What the GPU alone does
(the loop budget) is removed.
Usage: mirror_bodies.py REPO_ROOT"""
import os
import re
import sys
from collections import Counter

root = sys.argv[1]
GPU_ONLY = {"rc_budget", "rc_scene_access", "rc_real"}

# Statements only the shader has: the loop budget (rc_budget.glsl) and its bookkeeping.
GLSL_ONLY = [
    r"if\s*\(\s*!\s*budget_step\s*\(\s*\)\s*\)\s*(break|return[^;]*);",
    r"if\s*\(\s*!\s*budget_steps\s*\([^;]*\)\s*\)\s*(break|return[^;]*);",
]
# Spellings: shader name -> reference tokens.
GLSL_MAP = {
    "load_sphere": "spheres", "load_triangle": "triangles", "load_material": "materials",
    "load_light": "lights", "load_bvh_node": "bvh_nodes", "load_bvh_prim": "bvh_prims",
    "load_transform": "transforms", "load_vertex_normals": "normals", "load_quadric": "quadrics",
    "load_csg": "csg", "load_csg_instruction": "csg_program",
    "scene_light_count": "frame light_count", "scene_shadows": "frame shadows",
    "inversesqrt": "rsqrt",
}
# What the shader's accessors stand for: arrays and fields of the scene, which are operands.
SCENE_DATA = {v.split()[-1] for k, v in GLSL_MAP.items() if k.startswith(("load_", "scene_"))}
C_MAP = {"R_ABS": "abs", "R_SQRT": "sqrt", "fabs": "abs", "fabsf": "abs", "sqrtf": "sqrt", "powf": "pow",
         "fminf": "min", "fmaxf": "max", "fmin": "min", "fmax": "max", "floorf": "floor", "ceilf": "ceil",
         "frame_": "frame"}
# Vector operations of the C side (RV(op)(a, b)): the operator they stand for.
RV_OPS = {"add": "+", "sub": "-", "mul": "*", "scale": "*", "div": "/", "neg": "-", "dot": "dot",
          "cross": "cross", "length": "length", "normalize": "normalize", "abs": "abs", "min": "min",
          "max": "max", "make": None, "from": None}
# Names that carry no arithmetic: types, qualifiers, constructors, the C scene argument.
NEUTRAL = set("""real rvec3 vec3 dvec3 vec2 ivec3 uvec3 uvec4 uvec2 bvec3 float double int uint uint32_t int32_t
uint64_t bool const precise ray_shear sheared_triangle surface in out inout void static return if else for while break continue do struct
sc rvec3_from rv_get rmax3 rmin3 true false""".split())
OPS = {"+", "-", "*", "/", "<", ">", "<=", ">=", "==", "!=", "&&", "||", "!", "?", "%", "<<", ">>", "&", "|", "^",
       "+=", "-=", "*=", "/=", "++", "--", "~"}
TOKEN = re.compile(r"\s*(0[xX][0-9a-fA-F]+[uU]?|\d+\.\d*(?:[eE][-+]?\d+)?[fFlL]*|\.\d+(?:[eE][-+]?\d+)?[fF]?|"
                   r"\d+(?:[eE][-+]?\d+)?[uUlLfF]*|[A-Za-z_]\w*|->|<<=|>>=|<<|>>|<=|>=|==|!=|&&|\|\||"
                   r"\+\+|--|\+=|-=|\*=|/=|[-+*/%<>=!&|^~?:;,.()\[\]{}])")


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def bodies(text, c):
    """Public functions in order: name -> body text (between the outer braces)."""
    out = []
    if c:
        head = re.compile(r"^(?!static)[a-z][\w \*]*?\b(?:REF\((\w+)\)|ref_(\w+))\(", re.M)
    else:
        head = re.compile(r"^[a-z]\w* (\w+)\(", re.M)
    for m in head.finditer(text):
        name = next(g for g in m.groups() if g)
        i = text.index("{", m.end()) if "{" in text[m.end():] else -1
        semi = text.find(";", m.end())
        if i < 0 or (0 <= semi < i):
            continue  # a declaration
        depth, j = 0, i
        while True:
            if text[j] == "{":
                depth += 1
            elif text[j] == "}":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        params = text[m.end():i]
        out.append((name, params + " " + text[i + 1:j]))
    return out


def number(tok):
    t = tok.rstrip("uUlLfF") if not tok.lower().startswith("0x") else tok.rstrip("uU")
    try:
        return repr(float(int(t, 16)) if t.lower().startswith("0x") else float(t))
    except ValueError:
        return tok


def reduce(body, c):
    """(operands in order, operations counted)."""
    if not c:
        for pat in GLSL_ONLY:
            body = re.sub(pat, " ", body)
    toks = TOKEN.findall(body)
    operands, ops = [], Counter()
    prev = ";"
    i = 0
    while i < len(toks):
        t = toks[i]
        nxt = toks[i + 1] if i + 1 < len(toks) else ""
        if c and t in ("REF", "RV") and nxt == "(":
            name = toks[i + 2]
            i += 4  # REF ( name )
            if t == "RV":
                op = RV_OPS.get(name, name)
                if op:
                    ops[op] += 1
            else:
                ops[name] += 1  # a call of the twin
            prev = ")"
            continue
        if t == "->":
            t = "."
        if re.match(r"[A-Za-z_]", t) and re.fullmatch(r"(ref|gpu)_\w+|\w+_(triangle|shear|hit|surface)", t) and nxt != "(":
            prev = "type"  # a struct type: `ref_scene *sc`, `gpu_quadric q`
            i += 1
            continue
        if re.match(r"[A-Za-z_]", t):
            mapped = (C_MAP if c else GLSL_MAP).get(t, t)
            if c and mapped.startswith("ref_") and nxt == "(":
                mapped = mapped[4:]
                ops[mapped] += 1
            elif nxt == "(" and mapped not in NEUTRAL:
                # a call: the function's name is an operation, not an operand
                for w in mapped.split()[:-1]:
                    operands.append(w)
                if mapped.split()[-1] in SCENE_DATA:
                    operands.append(mapped.split()[-1])
                else:
                    ops[mapped.split()[-1]] += 1
            elif mapped not in NEUTRAL and not (re.match(r"[A-Za-z_]", nxt) and nxt not in NEUTRAL):
                operands.extend(mapped.split())
        elif re.match(r"[\d.]", t) and t != ".":
            operands.append(number(t))
        elif t in OPS:
            unary = prev in OPS or prev in ("(", ",", "=", ";", "{", "}", "return", "?", ":", "[", "type", "const")
            unary = unary or prev in NEUTRAL
            if c and t in ("*", "&") and unary:
                pass  # a pointer, not arithmetic
            elif t in ("+=", "-=", "*=", "/="):
                ops[t[0]] += 1
            else:
                ops[t] += 1
        prev = t
        i += 1
    return operands, ops


def main():
    failed, pairs, functions, differing = False, 0, 0, 0
    for base in sorted(os.listdir(os.path.join(root, "shaders"))):
        if not base.endswith(".glsl") or base[:-5] in GPU_ONLY:
            continue
        stem = base[:-5]
        glsl_path = os.path.join(root, "shaders", base)
        ref_path = os.path.join(root, "host", "ref", "ref_" + stem[3:] + ".c")
        if not os.path.exists(ref_path):
            print(f"FAIL: shaders/{base} has no CPU twin host/ref/{os.path.basename(ref_path)}")
            failed = True
            continue
        g = bodies(strip_comments(open(glsl_path).read()), False)
        r = bodies(strip_comments(open(ref_path).read()), True)
        gn, rn = [n for n, _ in g], [n for n, _ in r]
        pairs += 1
        functions += len(g)
        if gn != rn:
            print(f"FAIL: the functions of shaders/{base} and host/ref/{os.path.basename(ref_path)} differ:\n"
                  f"  shader:    {' '.join(gn)}\n  reference: {' '.join(rn)}")
            failed = True
            continue
        for (name, gb), (_, rb) in zip(g, r):
            go, gops = reduce(gb, False)
            ro, rops = reduce(rb, True)
            if go != ro or gops != rops:
                failed = True
                differing += 1
                k = next((k for k in range(min(len(go), len(ro))) if go[k] != ro[k]), min(len(go), len(ro)))
                print(f"FAIL: {name} ({base} / ref_{stem[3:]}.c): bodies differ")
                if go != ro:
                    print(f"  operands from #{k}: shader {go[k:k + 8]}, reference {ro[k:k + 8]}")
                if gops != rops:
                    print(f"  operations only in the shader {dict(gops - rops)}, only in the reference {dict(rops - gops)}")
    print(f"mirror bodies: {pairs} shader includes, {functions} functions, {differing} bodies differ after normalisation")
    return 1 if failed else 0


sys.exit(main())
