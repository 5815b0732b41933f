"""Cross-check the built-in table and the type rules against glslangValidator (GLSL ES 3.00).

For a deterministic sample of calls, operator uses and constructor calls - about half valid,
half wrong - a tiny ``#version 300 es`` fragment shader is compiled; glslang's accept/reject
must equal ours. When we accept, the program also assigns the result to a variable of the
type we computed, so the result type is checked too.

Skipped when glslangValidator is missing, unless the CI environment variable is set.
"""

from __future__ import annotations

import os
import random
import shutil
import subprocess
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from glslcheck.language import glsl_types as T
from glslcheck.language.builtin_functions import BUILTINS, resolve
from glslcheck.language.glsl_types import BY_NAME, Type

GLSLANG = shutil.which("glslangValidator")

pytestmark = pytest.mark.skipif(
    GLSLANG is None and not os.environ.get("CI"),
    reason="glslangValidator is not installed (set CI=1 to make this a failure)",
)

BASIC = [
    ty for name, ty in BY_NAME.items() if ty.is_basic and name not in ("mat2x2", "mat3x3", "mat4x4")
]
SAMPLERS = list(T.SAMPLERS.values())
SEED = 300


def _program(args: list[Type], expr_of, result: Type | None, const_args: bool) -> str:
    """A fragment shader that declares one variable per argument and evaluates the expression."""
    head, body = [], []
    names = []
    for i, a in enumerate(args):
        if a.is_opaque:
            head.append(f"uniform highp {a} s{i};")
            names.append(f"s{i}")
        else:
            const = "const " if const_args else ""
            body.append(f"    {const}{a} a{i} = {a}(1);")
            names.append(f"a{i}")
    expr = expr_of(names)
    body.append(f"    {result} r = {expr};" if result is not None else f"    {expr};")
    return "\n".join(
        [
            "#version 300 es",
            "precision highp float;",
            "precision highp int;",
            *head,
            "out vec4 o;",
            "void main() {",
            *body,
            "    o = vec4(0.0);",
            "}",
            "",
        ]
    )


def _compile_all(programs: list[str]) -> list[bool]:
    if GLSLANG is None:
        pytest.fail("glslangValidator is required when CI is set")
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i, src in enumerate(programs):
            p = Path(tmp) / f"case{i}.frag"
            p.write_text(src)
            paths.append(p)

        def ok(path: Path) -> bool:
            return subprocess.run([GLSLANG, str(path)], capture_output=True).returncode == 0

        with ThreadPoolExecutor(max_workers=os.cpu_count() or 4) as pool:
            return list(pool.map(ok, paths))


def _agreement(cases: list[tuple[str, bool, str]]) -> tuple[int, list[str]]:
    """cases: (label, we_accept, program). Returns (agreeing count, disagreement reports)."""
    verdicts = _compile_all([src for _, _, src in cases])
    bad = [
        f"{label}: ours={'accept' if mine else 'reject'} glslang="
        f"{'accept' if theirs else 'reject'}\n{src}"
        for (label, mine, src), theirs in zip(cases, verdicts)
        if mine != theirs
    ]
    return len(cases) - len(bad), bad


# --- built-in functions ----------------------------------------------------------------


def _mutate(rng: random.Random, params: tuple[Type, ...]) -> list[Type]:
    """A plausible mistake: one argument of the wrong type, or one argument too many/few."""
    args = list(params)
    roll = rng.random()
    if roll < 0.1 and args:
        args.pop(rng.randrange(len(args)))
    elif roll < 0.2:
        args.insert(rng.randrange(len(args) + 1), rng.choice([T.FLOAT, T.INT, T.VEC2]))
    else:
        i = rng.randrange(len(args))
        old = args[i]
        if old.is_opaque:
            args[i] = rng.choice([s for s in SAMPLERS if s != old])
        elif old.is_basic and rng.random() < 0.6 and not old.is_matrix:
            # Same shape, other base: the classic "int where float is needed".
            args[i] = T.vector(rng.choice([b for b in T.BASES if b != old.base]), old.size)
        else:
            args[i] = rng.choice([b for b in BASIC if b != old])
    return args


def _call_cases() -> list[tuple[str, bool, str]]:
    rng = random.Random(SEED)
    overloads = [ov for fn in BUILTINS.values() for ov in fn.overloads]
    valid = [rng.choice(BUILTINS[name].overloads) for name in sorted(BUILTINS)]
    valid += rng.sample(overloads, 100 - len(valid))
    calls = [(ov.name, list(ov.params)) for ov in valid]
    for _ in range(100):
        ov = rng.choice(overloads)
        calls.append((ov.name, _mutate(rng, ov.params)))
    cases = []
    for name, args in calls:
        r = resolve(name, args)
        mine = not isinstance(r, str)
        has_out = mine and bool(r.out_params) or name == "modf"
        src = _program(
            args,
            lambda ns, name=name: f"{name}({', '.join(ns)})",
            r.returns if mine else None,
            const_args=not has_out,
        )
        cases.append((f"{name}({', '.join(map(str, args))})", mine, src))
    return cases


def test_builtin_calls_agree_with_glslang(capsys):
    cases = _call_cases()
    accepted = sum(mine for _, mine, _ in cases)
    assert 80 <= accepted <= 120, accepted  # about half valid, half wrong
    agree, bad = _agreement(cases)
    with capsys.disabled():
        print(
            f"\nbuilt-in calls: glslang agreement {agree}/{len(cases)} ({accepted} accepted by us)"
        )
    assert not bad, "\n\n".join(bad[:10])


# --- operators, swizzles and constructors ----------------------------------------------

BINARY_OPS = ["+", "-", "*", "/", "%", "<", ">=", "==", "!=", "&&", "^^", "&", "|", "^", "<<", ">>"]
INTERESTING = [
    T.FLOAT,
    T.INT,
    T.UINT,
    T.BOOL,
    T.VEC2,
    T.VEC3,
    T.IVEC2,
    T.IVEC3,
    T.UVEC2,
    T.BVEC2,
    T.MAT2,
    T.MAT3,
    T.matrix(2, 3),
    T.matrix(3, 2),
]


# glslang accepts unary + on bool and bvec; the spec (5.9) lists the arithmetic unary
# operators as operating on integer or floating-point values only, and ANGLE - the compiler
# in front of WebGL and so of Shadertoy - rejects it. We follow the spec.
KNOWN_GLSLANG_LENIENCY = {"+bool", "+bvec2"}


def test_unary_plus_on_bool_is_rejected_although_glslang_accepts_it():
    assert isinstance(T.unary_result("+", T.BOOL), str)
    assert isinstance(T.unary_result("+", T.BVEC2), str)


def _operator_cases() -> list[tuple[str, bool, str]]:
    rng = random.Random(SEED + 1)
    cases = []
    for _ in range(160):
        op = rng.choice(BINARY_OPS)
        left = rng.choice(INTERESTING)
        right = left if rng.random() < 0.3 else rng.choice(INTERESTING)
        r = T.binary_result(op, left, right)
        mine = not isinstance(r, str)
        src = _program(
            [left, right],
            lambda ns, op=op: f"{ns[0]} {op} {ns[1]}",
            r if mine else None,
            const_args=False,
        )
        cases.append((f"{left} {op} {right}", mine, src))
    for op in ["-", "+", "!", "~", "++"]:
        for ty in INTERESTING:
            if op == "+" and ty.base == "bool":
                continue  # see KNOWN_GLSLANG_LENIENCY
            r = T.unary_result(op, ty)
            mine = not isinstance(r, str)
            src = _program(
                [ty], lambda ns, op=op: f"{op}{ns[0]}", r if mine else None, const_args=False
            )
            cases.append((f"{op}{ty}", mine, src))
    for ty in [T.VEC2, T.VEC4, T.IVEC3, T.BVEC2, T.FLOAT]:
        for fields in ["x", "xy", "zyx", "rgba", "xg", "stp", "xxxxx", "w", "q"]:
            r = T.swizzle_result(ty, fields)
            mine = not isinstance(r, str)
            src = _program(
                [ty], lambda ns, f=fields: f"{ns[0]}.{f}", r if mine else None, const_args=False
            )
            cases.append((f"{ty}.{fields}", mine, src))
    return cases


def _constructor_cases() -> list[tuple[str, bool, str]]:
    rng = random.Random(SEED + 2)
    targets = [
        T.FLOAT,
        T.INT,
        T.UINT,
        T.BOOL,
        T.VEC2,
        T.VEC3,
        T.VEC4,
        T.IVEC3,
        T.BVEC4,
        T.MAT2,
        T.MAT3,
        T.matrix(2, 3),
        T.matrix(4, 2),
    ]
    pieces = [T.FLOAT, T.INT, T.BOOL, T.VEC2, T.VEC3, T.VEC4, T.IVEC2, T.MAT2, T.MAT3]
    cases = []
    for _ in range(120):
        target = rng.choice(targets)
        args = [rng.choice(pieces) for _ in range(rng.randint(1, 4))]
        mine = T.constructor_check(target, args) is None
        src = _program(
            args,
            lambda ns, tg=target: f"{tg}({', '.join(ns)})",
            target if mine else None,
            const_args=False,
        )
        cases.append((f"{target}({', '.join(map(str, args))})", mine, src))
    return cases


def test_operators_and_constructors_agree_with_glslang(capsys):
    cases = _operator_cases() + _constructor_cases()
    agree, bad = _agreement(cases)
    with capsys.disabled():
        print(f"\noperators/swizzles/constructors: glslang agreement {agree}/{len(cases)}")
    assert not bad, "\n\n".join(bad[:10])


# --- reserved words, built-in variables, Shadertoy uniforms ----------------------------


def _shader(decls: str, body: str) -> str:
    return (
        "#version 300 es\nprecision highp float;\nprecision highp int;\n"
        f"{decls}\nout vec4 o;\nvoid main() {{\n{body}\n    o = vec4(0.0);\n}}\n"
    )


def test_reserved_words_and_keywords_are_not_identifiers():
    from glslcheck.language.builtin_functions import KEYWORDS, RESERVED_WORDS

    words = sorted(RESERVED_WORDS | KEYWORDS)
    fine = ["buffer", "precise", "sampler", "texture2D", "main2", "iTime"]
    programs = [_shader("", f"    float {w} = 1.0;") for w in words + fine]
    verdicts = _compile_all(programs)
    wrongly_accepted = [w for w, ok in zip(words, verdicts) if ok]
    wrongly_rejected = [w for w, ok in zip(fine, verdicts[len(words) :]) if not ok]
    assert not wrongly_accepted and not wrongly_rejected


def test_builtin_variable_types_match_glslang():
    from glslcheck.language.builtin_functions import BUILTIN_VARIABLES

    body = []
    for name, var in BUILTIN_VARIABLES.items():
        if var.type.is_struct:
            body += [f"    float x_{name}_{f} = {name}.{f};" for f, _ in var.type.fields]
        elif var.storage == "out":
            body.append(f"    {name} = {var.type}(0);")
        else:
            body.append(f"    {var.type} v_{name} = {name};")
    assert _compile_all([_shader("", "\n".join(body))]) == [True]


def test_shadertoy_uniform_declarations_compile():
    from glslcheck.language.builtin_functions import SHADERTOY_UNIFORMS

    decls = "\n".join(
        f"uniform {u.type} {name}{'' if u.array_size is None else f'[{u.array_size}]'};"
        for name, u in SHADERTOY_UNIFORMS.items()
    )
    body = "\n".join(
        f"    {u.declared_type.element if u.array_size else u.declared_type} "
        f"x_{name} = {name}{'[0]' if u.array_size else ''};"
        for name, u in SHADERTOY_UNIFORMS.items()
        if not u.type.is_opaque
    )
    assert _compile_all([_shader(decls, body)]) == [True]
