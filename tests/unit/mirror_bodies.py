#!/usr/bin/env python3
"""The mirror gate (docs/design.md §9): every function of shaders/rc_X.glsl has its twin in
host/ref/ref_X.c, in the same order, and the two bodies compute the same thing.

Bodies are compared after both are reduced to what the arithmetic depends on:
- the operands, in order: every variable, field and constant as written, numbers by value
  (GLSL's 2.0 is C's 2); C's prefix calls (RV(sub)(a, b)) and GLSL's infix operators
  (a - b) keep their operands in the same order, so a swapped, missing or extra operand
  shows;
- the operations, counted: + - * / and comparisons (C's RV(add), RV(scale), RV(neg) count
  as theirs), and the named functions (dot, sqrt, normalize, ...).
Before that, what differs only in spelling is mapped (the tables below), local constants
that name one value (`const real far = (real)RC_T_FAR;`) are replaced by that value, and
what the GPU alone does (the loop budget and its blame) is removed.

What still differs is a difference of form the reduction cannot see through (the shader's
vector min against the reference's per-component calls, a division GLSL writes as v / s
and the reference as the product with 1 / s) or a difference of substance. Each one is
written, exactly as this script prints it and with the reason, in mirror_differences.txt
beside this file. The gate fails when a function's difference is not the one recorded
there: a formula changed on one side only, or a recorded difference went away (then the
entry is stale and must go). `--write` rewrites the file from the sources, keeping the
reasons already given; a new entry gets `why: TODO`, which fails until someone writes why.

Usage: mirror_bodies.py REPO_ROOT [--write]"""
import difflib
import os
import re
import sys
from collections import Counter

GPU_ONLY = {"rc_budget", "rc_scene_access", "rc_real"}
LEDGER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mirror_differences.txt")

# Statements only the shader has: the loop budget (rc_budget.glsl) and who it blames.
GLSL_ONLY = [
    r"if\s*\(\s*!\s*budget_(?:step|steps|take)\s*\([^;{]*\)\s*\)\s*(?:\{[^{}]*\}|break;|return[^;]*;)",
    r"\bbudget_blame\s*=[^;]*;",
    r"\bhas_kind\s*\(\s*\w+\s*\)\s*&&",  # a specialization constant: the feature is compiled out
    r"!\s*has_kind\s*\(\s*\w+\s*\)\s*\|\|",  # the same, where the feature's absence takes the common path
    # A light pass (raycast.comp): a later pass drops what no light contributes, and the
    # first pass's guard of it; the pass's lights are, on the CPU, all of them.
    r"\bif\s*\(\s*light_pass_begin\s*\(\s*\)\s*!=\s*0u\s*\)[^;]*;",
    r"\bif\s*\(\s*light_pass_begin\s*\(\s*\)\s*==\s*0u\s*\)",
]
GLSL_PASS_BOUNDS = [(r"\blight_pass_begin\s*\(\s*\)", "0u"), (r"\blight_pass_end\s*\(\s*\)", "scene_light_count()")]
# Statements only the reference has: its work counter (--stats of the CPU backend).
C_ONLY = [r"\bref_work\s*(?:\+\+|\+=[^;]*);"]
# The reference's `x = RV(add)(x, y)` is the shader's `x += y`.
C_COMPOUND = (r"\b(\w+)\s*=\s*RV\((add|sub|mul)\)\(\s*\1\s*,", lambda m: f"{m.group(1)} {RV_OPS[m.group(2)]}= (")
# Both sides: a precise temporary that is returned at once is its expression; a pointer
# starts as NULL where the shader declares the struct; a flag test `(x & F) != 0` is `(x & F)`;
# a splat constructor vec3(0.0) has three components.
COMMON = [
    (r"(?:precise\s+)?\w+\s+(\w+)\s*=\s*([^;]*);\s*return\s+\1\s*;", r"return \2;"),
    (r"\s*=\s*NULL\b", ""),
    (r"\)\s*!=\s*0u?\b", ")"),
    (r"\b([rd]?vec3)\(\s*([\d.]+)\s*\)", r"\1(\2, \2, \2)"),
    (r"^\s*#\s*(?:if|ifdef|else|endif)\b[^\n]*", " "),
]
# Shader spellings -> reference tokens. The accessors stand for the scene's arrays.
GLSL_MAP = {
    "load_sphere": "spheres", "load_triangle": "triangles", "load_material": "materials",
    "load_light": "lights", "load_bvh_node": "bvh_nodes", "load_bvh_prim": "bvh_prims",
    "load_transform": "transforms", "load_vertex_normals": "normals", "load_quadric": "quadrics",
    "load_csg": "csg", "load_csg_instruction": "csg_program",
    "inversesqrt": "rsqrt", "RC_OFFSET_BITS": "bits_of", "RC_OFFSET_FROM_BITS": "from_bits",
    "select_min": "min", "select_max": "max",  # rc_real.glsl's selects: the reference's rmin, rmax
    "pixel": "px py",
}
SCENE_DATA = {v for k, v in GLSL_MAP.items() if k.startswith("load_")}
# Reference spellings -> shader tokens.
C_MAP = {"R_ABS": "abs", "R_SQRT": "sqrt", "fabs": "abs", "fabsf": "abs", "sqrtf": "sqrt", "powf": "pow",
         "fminf": "min", "fmaxf": "max", "fmin": "min", "fmax": "max", "floorf": "floor", "ceilf": "ceil", "R_FLOOR": "floor",
         "rmin": "min", "rmax": "max", "rcm_eq_f": "==", "R_FREXP": "frexp", "frexpf": "frexp"}
# Vector operations of the C side (RV(op)(a, b)): the operator they stand for.
RV_OPS = {"add": "+", "sub": "-", "mul": "*", "scale": "*", "div": "/", "divs": "/", "neg": "-", "dot": "dot", "eq": "==",
          "cross": "cross", "length": "length", "normalize": "normalize", "abs": "abs", "min": "min",
          "max": "max", "reflect": "reflect", "make": None, "from": None}
# Names that carry no arithmetic: types, qualifiers, constructors, conversions, the C scene
# argument and its frame pointer, GLSL's .xyz.
NEUTRAL = set("""real rvec3 rvec4 vec3 dvec3 vec2 ivec3 uvec3 uvec4 uvec2 bvec3 float double int uint uint32_t int32_t
uint64_t int64_t bool const precise ray_shear sheared_triangle surface hit_record in out inout void static return
if else for while break continue do struct sc rvec3_from vec3_from rv_get true false v3 rcm_xyz rcm_make_f rcm_to_f
RC_OFFSET_INT offset_int xyz dont_unroll""".split())
SPEC_CONSTANTS = ["sphere_formula", "triangle_formula", "offset_strategy", "offset_epsilon", "use_bvh", "certify"]
OPS = {"+", "-", "*", "/", "<", ">", "<=", ">=", "==", "!=", "&&", "||", "!", "?", "%", "<<", ">>", "&", "|", "^",
       "+=", "-=", "*=", "/=", "++", "--", "~"}
TOKEN = re.compile(r"\s*(0[xX][0-9a-fA-F]+[uU]?|\d+\.\d*(?:[eE][-+]?\d+)?[fFlL]*|\.\d+(?:[eE][-+]?\d+)?[fF]?|"
                   r"\d+(?:[eE][-+]?\d+)?[uUlLfF]*|[A-Za-z_]\w*|->|<<=|>>=|<<|>>|<=|>=|==|!=|&&|\|\||"
                   r"\+\+|--|\+=|-=|\*=|/=|[-+*/%<>=!&|^~?:;,.()\[\]{}#])")
# `const TYPE NAME = VALUE;` where VALUE is one name, field chain or number, maybe cast.
ALIAS = re.compile(r"\bconst\s+\w+\s*\*?\s*(\w+)\s*=\s*(?:\(\s*\w+\s*\)\s*|\w+\s*\(\s*)?"
                   r"([A-Za-z_][\w.>-]*|[\d.eE+-]+[fFuU]?)\s*\)?\s*;")


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def bodies(text, c):
    """Public functions in order: (name, parameters and body text)."""
    out = []
    if c:
        head = re.compile(r"^(?!static)[a-z][\w \*]*?\b(?:REF\((\w+)\)|ref_(\w+))\(", re.M)
    else:
        head = re.compile(r"^[a-z]\w* (\w+)\(", re.M)
    for m in head.finditer(text):
        name = next(g for g in m.groups() if g)
        i = text.find("{", m.end())
        semi = text.find(";", m.end())
        if i < 0 or (0 <= semi < i):
            continue  # a declaration
        depth, j = 0, i
        while True:
            depth += {"{": 1, "}": -1}.get(text[j], 0)
            if depth == 0 and text[j] == "}":
                break
            j += 1
        out.append((name, text[m.end():i] + " { " + text[i + 1:j]))
    return out


def number(tok):
    t = tok.rstrip("uU") if tok.lower().startswith("0x") else tok.rstrip("uUlLfF")
    try:
        return repr(float(int(t, 16)) if t.lower().startswith("0x") else float(t))
    except ValueError:
        return tok


def inline_aliases(body):
    for m in list(ALIAS.finditer(body)):
        name, value = m.group(1), m.group(2)
        body = body.replace(m.group(0), " ")
        body = re.sub(r"(?<![\w.>])" + name + r"\b", value, body)
    return body


def call_args(text, start):
    """The arguments of the call whose '(' is at text[start], split at top-level commas
    (parentheses and brackets balanced), and the index just past its ')'."""
    depth, args, arg_start = 0, [], start + 1
    for i in range(start, len(text)):
        ch = text[i]
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
            if depth == 0:
                args.append(text[arg_start:i])
                return args, i + 1
        elif ch == "," and depth == 1:
            args.append(text[arg_start:i])
            arg_start = i + 1
    return None, len(text)


def scalar_first(body):
    """RV(scale)(v, s) is GLSL's s * v: its arguments swapped, so that the operands come in
    the shader's order (the scalar first, as the shaders write it), nested calls included."""
    out, i = [], 0
    key = "RV(scale)("
    while True:
        j = body.find(key, i)
        if j < 0:
            out.append(body[i:])
            return "".join(out)
        args, end = call_args(body, j + len(key) - 1)
        if not args or len(args) != 2:
            out.append(body[i:j + len(key)])
            i = j + len(key)
            continue
        v, s_ = (scalar_first(a).strip() for a in args)
        out.append(body[i:j] + f"RV(scale)({s_}, {v})")
        i = end


def reduce(body, c):
    """(operands in order, operations counted)."""
    if not c:
        for pat in GLSL_ONLY:
            body = re.sub(pat, " ", body)
        for pat, rep in GLSL_PASS_BOUNDS:
            body = re.sub(pat, rep, body)
        body = re.sub(r"\bpixel\.x\b", "px", re.sub(r"\bpixel\.y\b", "py", body))
        body = re.sub(r"\bscene_(\w+)\s*\(\s*\)", r"frame.\1", body)
    else:
        for pat in C_ONLY:
            body = re.sub(pat, " ", body)
        body = re.sub(*C_COMPOUND, body)
        body = scalar_first(body)
        body = re.sub(r"\brv_get\(\s*(\w+)\s*,\s*(\w+)\s*\)", r"\1[\2]", body)  # GLSL's v[k]
    for pat, rep in COMMON:
        body = re.sub(pat, rep, body, flags=re.M)
    body = inline_aliases(body)
    if c:  # the shader's specialization constants are the frame's fields on the CPU
        body = re.sub(r"\bframe\s*(?:->|\.)\s*(" + "|".join(SPEC_CONSTANTS) + r")\b", r"\1", body)
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
            op = RV_OPS.get(name, name) if t == "RV" else name
            if op:
                ops[op] += 1
            prev = ")"
            continue
        if t == "->":
            t = "."
        if c and re.fullmatch(r"ref_\w+", t) and nxt not in ("(", "*") and not re.match(r"[A-Za-z_]", nxt):
            t = t[4:]  # a global the shader has without the prefix: ref_spawned_ray
        elif re.fullmatch(r"(ref|packed)_\w+|\w+_(triangle|shear|hit|surface)", t) and nxt != "(":
            prev = "type"  # a struct type: `ref_scene *sc`, `packed_quadric q`
            i += 1
            continue
        if re.match(r"[A-Za-z_]", t):
            mapped = (C_MAP if c else GLSL_MAP).get(t, t)
            if c and mapped == "rmax3" and nxt == "(":
                ops["max"] += 2  # max(max(a, b), c)
            elif c and mapped.startswith("ref_") and nxt == "(":
                ops[mapped[4:]] += 1
            elif nxt == "(" and mapped not in NEUTRAL:
                if mapped in SCENE_DATA:
                    operands.append(mapped)  # an array of the scene, indexed
                else:
                    ops[mapped] += 1  # a call: the function is an operation, not an operand
            elif mapped not in NEUTRAL and not (re.match(r"[A-Za-z_]", nxt) and nxt not in NEUTRAL):
                operands.extend(mapped.split())
        elif re.match(r"[\d.]", t) and t != ".":
            operands.append(number(t))
        elif t in OPS:
            unary = prev in OPS or prev in ("(", ",", "=", ";", "{", "}", "return", "?", ":", "[", "type")
            unary = unary or prev in NEUTRAL
            if c and t == "*" and i + 2 < len(toks) and toks[i + 2] in ("=", "+=", "-=", "*=", "/="):
                pass  # `*out = x`, an out parameter written
            elif c and t in ("*", "&") and unary:
                pass  # a pointer, not arithmetic
            elif t in ("+=", "-=", "*=", "/="):
                ops[t[0]] += 1
            else:
                ops[t] += 1
        prev = t
        i += 1
    return operands, ops


def difference(g, r):
    """The lines that say how the reduced bodies differ; [] when they do not."""
    (go, gops), (ro, rops) = g, r
    lines = []
    sm = difflib.SequenceMatcher(a=go, b=ro, autojunk=False)
    for tag, i1, i2, j1, j2 in sm.get_opcodes():
        if tag != "equal":
            lines.append(f"operands: shader [{' '.join(go[i1:i2])}] reference [{' '.join(ro[j1:j2])}]")
    only_g, only_r = gops - rops, rops - gops
    if only_g or only_r:
        fmt = lambda cnt: " ".join(f"{k}:{cnt[k]}" for k in sorted(cnt))
        lines.append(f"operations: shader [{fmt(only_g)}] reference [{fmt(only_r)}]")
    return lines


LEDGER_HEAD = """\
# Reviewed differences between shader functions (shaders/rc_*.glsl) and their CPU twins
# (host/ref/ref_*.c), checked by tests/unit/mirror_bodies.py (docs/design.md §9). Each entry
# is the function, the reason its two bodies differ after normalisation, and the difference
# exactly as the script computes it: operands that one side has where the other has others
# (in order), then operations that one side counts more of. The gate fails when a body
# changes so that its difference is no longer the one below. Rewrite the difference lines
# with `tests/unit/mirror_bodies.py . --write` (the reasons are kept); write the reasons.
"""


def read_ledger():
    """function -> (why, difference lines)."""
    entries, name = {}, None
    if not os.path.exists(LEDGER):
        return entries
    for line in open(LEDGER):
        line = line.rstrip("\n")
        if not line.strip() or line.startswith("#"):
            continue
        if not line.startswith(" "):
            name = line.split("#")[0].strip()
            entries[name] = ["", []]
        elif line.strip().startswith("why:"):
            entries[name][0] = line.strip()[4:].strip()
        else:
            entries[name][1].append(line.strip())
    return entries


def main():
    root = sys.argv[1]
    write = "--write" in sys.argv[2:]
    failures, pairs, functions, found = [], 0, 0, {}
    for base in sorted(os.listdir(os.path.join(root, "shaders"))):
        if not base.endswith(".glsl") or base[:-5] in GPU_ONLY:
            continue
        ref_name = "ref_" + base[3:-5] + ".c"
        ref_path = os.path.join(root, "host", "ref", ref_name)
        if not os.path.exists(ref_path):
            failures.append(f"shaders/{base} has no CPU twin host/ref/{ref_name}")
            continue
        g = bodies(strip_comments(open(os.path.join(root, "shaders", base)).read()), False)
        r = bodies(strip_comments(open(ref_path).read()), True)
        gn, rn = [n for n, _ in g], [n for n, _ in r]
        if gn != rn:
            failures.append(f"the functions of shaders/{base} and host/ref/{ref_name} differ:\n"
                            f"  shader:    {' '.join(gn)}\n  reference: {' '.join(rn)}")
            continue
        pairs += 1
        functions += len(g)
        for (name, gb), (_, rb) in zip(g, r):
            diff = difference(reduce(gb, False), reduce(rb, True))
            if diff:
                found[name] = (f"{base} / {ref_name}", diff)

    ledger = read_ledger()
    if write and failures:
        # A pair not compared would lose its entries, and their reasons, from the file.
        for f in failures:
            print("FAIL: " + f)
        print("not written: fix the pairs above first")
        return 1
    if write:
        with open(LEDGER, "w") as f:
            f.write(LEDGER_HEAD)
            for name, (files, diff) in found.items():
                why = ledger.get(name, ["TODO"])[0] or "TODO"
                f.write(f"\n{name}  # {files}\n  why: {why}\n" + "".join(f"  {d}\n" for d in diff))
        print(f"wrote {LEDGER}: {len(found)} entries")
        return 0
    for name, (files, diff) in found.items():
        if name not in ledger:
            failures.append(f"{name} ({files}): the bodies differ, and mirror_differences.txt records no "
                            "difference:\n" + "".join(f"  {d}\n" for d in diff).rstrip())
        elif ledger[name][1] != diff:
            failures.append(f"{name} ({files}): the bodies differ otherwise than mirror_differences.txt "
                            "records.\n  now:\n" + "".join(f"    {d}\n" for d in diff)
                            + "  recorded:\n" + "".join(f"    {d}\n" for d in ledger[name][1]).rstrip())
        elif not ledger[name][0] or ledger[name][0] == "TODO":
            failures.append(f"{name}: mirror_differences.txt gives no reason (why:) for its difference")
    for name in ledger:
        if name not in found:
            failures.append(f"{name}: recorded in mirror_differences.txt, but its bodies no longer differ "
                            "(or it is gone): remove the entry")
    for f in failures:
        print("FAIL: " + f)
    print(f"mirror bodies: {pairs} shader includes, {functions} functions, {functions - len(found)} alike "
          f"after normalisation, {len(found)} with a recorded difference")
    if failures:
        print("A formula changed on one side only, or a difference is new: make the twins agree, or, if the "
              "difference is one of form, run tests/unit/mirror_bodies.py . --write and give the reason.")
    return 1 if failures else 0


sys.exit(main())
