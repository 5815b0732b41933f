"""The generated Python can do nothing but arithmetic (bad input must never run code), with hostile
names in every place a GLSL name can be declared.

tests/numpy/test_transpile.py has the transpiler owner's catalogue (function names, locals,
struct fields). This one puts a second catalogue, aimed at Python escapes (dunders, builtins,
modules, the generator's own prefixes), into the places that one does not: global variables,
consts, parameters, loop counters, struct type names, and names that come from a macro. For
each, the generated module must (1) use none of the names as a bare Python identifier outside
comments and strings, (2) contain no dunder attribute access at all, (3) run with empty
`__builtins__` and render.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from glslcheck.backends.numpy_engine import program as P
from glslcheck.backends.numpy_engine.transpile import transpile_shader
from glslcheck.language.builtin_functions import KEYWORDS, RESERVED_WORDS

NAMES = [
    "__import__",
    "__builtins__",
    "__class__",
    "__subclasses__",
    "__globals__",
    "__code__",
    "__getattribute__",
    "__dict__",
    "__name__",
    "eval",
    "exec",
    "compile",
    "os",
    "sys",
    "subprocess",
    "print",
    "open",
    "input",
    "exit",
    "quit",
    "vars",
    "locals",
    "self",
    "cls",
    "np",
    "numpy",
    "math",
    "lambda_",
    "None_",
    "rt",
    "X",
    "S",
    "tile",
    "lanes",
    "mask",
    "v_x",
    "f_f",
    "g_g",
    "C_1",
    "Z_float",
    "__",
    "_",
    "___x",
]

# Python keywords are GLSL-legal names too.
NAMES += ["lambda", "def", "class", "import", "global", "nonlocal", "yield", "None", "True", "pass"]

POSITIONS = {
    "global": lambda n: (f"float {n} = 0.25;\n", f"acc += {n};"),
    "const": lambda n: (f"const float {n} = 0.5;\n", f"acc += {n};"),
    "parameter": lambda n: (f"float h(float {n}) {{ return {n} * 2.0; }}\n", "acc += h(0.125);"),
    "loop counter": lambda n: ("", f"for (int {n} = 0; {n} < 2; {n}++) {{ acc += float({n}); }}"),
    "struct type": lambda n: (f"struct {n} {{ float a; }};\n", f"{n} s = {n}(0.75); acc += s.a;"),
    "macro": lambda n: (f"#define M {n}\nfloat M = 0.375;\n", f"acc += {n};"),
}


def _shader(position: str, name: str, plain: bool | None = None) -> dict[str, str]:
    """make_shader's arguments: a Shadertoy Image tab, or for a name with `__` (an error in a
    tab: no browser compiles it; glslcheck/semantics/webgl_rules.py) a plain GLSL ES file."""
    decl, use = POSITIONS[position](name)
    body = (
        f"    float acc = 0.0;\n    {use}\n    fragColor = vec4(acc, fragCoord.x * 0.1, 0.0, "
        "1.0);\n}\n"
    )
    if plain if plain is not None else "__" in name:
        return {
            "GLSL": "#version 300 es\nprecision highp float;\nout vec4 fragColor;\n"
            + decl
            + "void main() {\n    vec2 fragCoord = gl_FragCoord.xy;\n"
            + body
        }
    return {"image": decl + "void mainImage(out vec4 fragColor, in vec2 fragCoord) {\n" + body}


def _code_identifiers(source: str) -> set[str]:
    code = [
        re.sub(r"'[^']*'|\"[^\"]*\"", '""', line.split("#", 1)[0]) for line in source.splitlines()
    ]
    return {m.group(0) for line in code for m in re.finditer(r"(?<![.\w])[A-Za-z_]\w*", line)}


@pytest.mark.parametrize("position", sorted(POSITIONS))
def test_hostile_names_are_mangled_and_inert(make_shader, position):
    for name in NAMES:
        if name in RESERVED_WORDS or name in KEYWORDS:  # `input`, `class`: GLSL refuses them
            continue
        if (
            name
            in {
                "lambda",
                "def",
                "class",
                "import",
                "global",
                "nonlocal",
                "yield",
                "None",
                "True",
                "pass",
            }
            and position == "struct type"
        ):
            continue  # covered by the other positions; keeps the struct case simple
        shader = make_shader(**_shader(position, name))
        src = transpile_shader(shader).source
        # Names the generator itself writes for any shader (rt, X, numpy in the standalone
        # footer, ...) are its own: the user's name must not add a bare use of any of them.
        own = _code_identifiers(
            transpile_shader(make_shader(**_shader(position, "q", "__" in name))).source
        )
        assert name not in _code_identifiers(src) - own, (
            f"{position} {name!r} reached the generated code unmangled"
        )
        code = "\n".join(line.split("#", 1)[0] for line in src.splitlines())
        assert not re.search(r"\.\s*__\w+", code), f"{position} {name!r}: dunder attribute access"
        assert not re.search(r"\b(eval|exec|__import__|getattr|setattr|open|compile)\s*\(", code), (
            name
        )
        prog = P.compile_numpy(shader)
        assert prog.module()["__builtins__"] == {}
        img = prog.render(size=(4, 2))
        assert img.shape == (2, 4, 4) and np.isfinite(img).all(), (position, name)
