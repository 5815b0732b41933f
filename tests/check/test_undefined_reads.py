"""The checker's undefined reads (semantics/analysis/undefined.py): each shader of
tests/verify/undefined marks its undefined reads with `// undefined: KIND` (one word per read
on the line, by GLSL ES 3.00's text); the analysis must find exactly those (`origins`), and
`check` warn at each (an out parameter left unwritten on a path is no warning of its own)."""

from __future__ import annotations

from pathlib import Path

import pytest

from glslcheck.cli.main import main
from glslcheck.frontend.parser import parse_shader
from glslcheck.semantics import check
from glslcheck.semantics.analysis import origins, undefined_reads
from glslcheck.shadertoy.sources import load_shader

CASES = Path(__file__).resolve().parents[1] / "verify" / "undefined"
SHADERS = sorted(p.name for p in CASES.glob("*.glsl"))


def _marked(path: Path) -> list[tuple[int, str]]:
    out = []
    for n, line in enumerate(path.read_text().splitlines(), 1):
        if "// undefined:" in line:
            out += [(n, kind) for kind in line.split("// undefined:")[1].split()]
    return sorted(out)


def _model(path: Path):
    return check(parse_shader(load_shader(path), "Image"))


@pytest.mark.parametrize("name", SHADERS)
def test_reads_are_the_marked_ones(name):
    model = _model(CASES / name)
    found = sorted((u.loc.line, u.kind) for u in origins(model).values())
    assert found == _marked(CASES / name)
    warned = [(u.loc.line, u.kind) for u in undefined_reads(model)]
    assert sorted(warned) == [m for m in found if m[1] != "out-parameter-unwritten"]


@pytest.mark.parametrize("name", SHADERS)
def test_check_warns_at_each_read(name, capsys):
    assert main(["check", str(CASES / name)]) == 0  # warnings, not errors
    err = capsys.readouterr().err
    for line, kind in _marked(CASES / name):
        if kind != "out-parameter-unwritten":
            assert f"{CASES / name}:{line}:" in err and "warning" in err


def _reads(make_shader, body: str, helpers: str = "") -> list[tuple[str, str]]:
    shader = make_shader(
        helpers + "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n" + body + "\n}\n"
    )
    model = check(parse_shader(shader, "Image"))
    return [(u.kind, u.node.name if u.symbol else "") for u in undefined_reads(model)]


@pytest.mark.parametrize(
    "body, found",
    [
        # the body of a counting loop whose condition holds at its start runs at least once
        ("float a[2];\nfor (int i = 0; i < 2; i++) a[i] = 1.0;\nfragColor = vec4(a[1]);", []),
        # ... one whose bound is not known may not run
        (
            "float a[2];\nfor (int i = 0; i < int(fragCoord.x); i++) a[i] = 1.0;\n"
            "fragColor = vec4(a[1]);",
            [("uninitialized-local", "a")],
        ),
        # while (true) is left only by its break, after the assignment
        ("float h;\nwhile (true) { h = 1.0; break; }\nfragColor = vec4(h);", []),
        # a break before the assignment leaves it unassigned
        (
            "float h;\nwhile (true) { if (fragCoord.x > 1.0) break; h = 1.0; break; }\n"
            "fragColor = vec4(h);",
            [("uninitialized-local", "h")],
        ),
        # .length() of an array reads no element
        ("float a[3];\nfragColor = vec4(float(a.length()));", []),
        # mainImage's own out parameter read before it is written
        ("fragColor.rgb += vec3(1.0);", [("out-parameter", "fragColor")]),
    ],
)
def test_paths(make_shader, body, found):
    assert _reads(make_shader, body) == found


def test_out_argument_writes_and_inout_argument_reads(make_shader):
    helpers = (
        "void set(out float v) { v = 1.0; }\nvoid bump(inout float v) { v += 1.0; }\n"
        "void pass_on(out float v) { set(v); bump(v); }\n"
    )
    assert _reads(make_shader, "float x;\npass_on(x);\nfragColor = vec4(x);", helpers) == []
    helpers2 = "void bump(inout float v) { v += 1.0; }\nvoid f(out float v) { bump(v); }\n"
    found = _reads(make_shader, "float x;\nf(x);\nfragColor = vec4(x);", helpers2)
    assert found == [("out-parameter", "v")]


# A global declared without an initializer, followed from mainImage across its calls
GLOBAL = "float g;\n"


@pytest.mark.parametrize(
    "helpers, body, found",
    [
        # read by mainImage before anything assigns it
        ("", "fragColor = vec4(g);", [("uninitialized-global", "g")]),
        # assigned first
        ("", "g = 1.0;\nfragColor = vec4(g);", []),
        # a callee that assigns it on every path (if/else) counts as assigning it
        (
            "void set(float x) { if (x > 1.0) g = 1.0; else g = 2.0; }\n",
            "set(fragCoord.x);\nfragColor = vec4(g);",
            [],
        ),
        # ... one that assigns it on one path only does not
        (
            "void set(float x) { if (x > 1.0) g = 1.0; }\n",
            "set(fragCoord.x);\nfragColor = vec4(g);",
            [("uninitialized-global", "g")],
        ),
        # ... nor one that may return before the assignment
        (
            "void set(float x) { if (x > 1.0) return; g = 1.0; }\n",
            "set(fragCoord.x);\nfragColor = vec4(g);",
            [("uninitialized-global", "g")],
        ),
        # assigned in a loop body that may run zero times, in a callee
        (
            "float march(float x) { for (int i = 0; i < int(x); i++) g = 1.0; return x; }\n",
            "fragColor = vec4(march(fragCoord.x) + g);",
            [("uninitialized-global", "g")],
        ),
        # ... in a counting loop whose body runs
        (
            "float march(float x) { for (int i = 0; i < 4; i++) g = x; return x; }\n",
            "fragColor = vec4(march(fragCoord.x) + g);",
            [],
        ),
        # ... in while (true), left only by its break after the assignment
        (
            "void set(float x) { while (true) { g = x; break; } }\n",
            "set(fragCoord.x);\nfragColor = vec4(g);",
            [],
        ),
        # read in a callee called before the call that assigns it: the read is the callee's
        (
            "float use() { return g * 2.0; }\nvoid set() { g = 1.0; }\n",
            "float a = use();\nset();\nfragColor = vec4(a + g);",
            [("uninitialized-global", "g")],
        ),
        # ... and after it: nothing
        (
            "float use() { return g * 2.0; }\nvoid set() { g = 1.0; }\n",
            "set();\nfragColor = vec4(use());",
            [],
        ),
        # a read two calls deep, reached from mainImage with nothing assigned
        (
            "float inner() { return g; }\nfloat outer() { return inner() + 1.0; }\n",
            "fragColor = vec4(outer());",
            [("uninitialized-global", "g")],
        ),
        # the read in a loop's condition of a callee, assigned only in the loop's body
        (
            "void walk() { while (g < 1.0) g += 0.5; }\n",
            "walk();\nfragColor = vec4(g);",
            [("uninitialized-global", "g")],
        ),
        # passed as an out argument: the call assigns it
        ("void set(out float v) { v = 1.0; }\n", "set(g);\nfragColor = vec4(g);", []),
        # ... as an inout argument: a read
        (
            "void bump(inout float v) { v += 1.0; }\n",
            "bump(g);\nfragColor = vec4(g);",
            [("uninitialized-global", "g")],
        ),
        # a function no path from mainImage calls is not followed
        ("float unused() { return g; }\n", "fragColor = vec4(1.0);", []),
        # a ?: arm that calls the assigning function is one path only
        (
            "float set() { g = 1.0; return 0.0; }\n",
            "float a = fragCoord.x > 1.0 ? set() : 1.0;\nfragColor = vec4(a + g);",
            [("uninitialized-global", "g")],
        ),
    ],
)
def test_globals_across_calls(make_shader, helpers, body, found):
    assert _reads(make_shader, body, GLOBAL + helpers) == found


@pytest.mark.parametrize(
    "declaration",
    [
        "float g = 0.5;\n",
        "const float g = 0.5;\n",
        "#define g iTime\n",
        "float h;\nfloat g = 0.5;\n",
    ],
)
def test_globals_with_a_value_are_not_findings(make_shader, declaration):
    assert _reads(make_shader, "fragColor = vec4(g);", declaration) == []


def test_a_plain_shaders_uniform_and_output_are_not_findings(make_shader):
    shader = make_shader(
        GLSL="#version 300 es\nprecision highp float;\nuniform float u;\nout vec4 o;\n"
        "void main() { o = vec4(u); o.x += 1.0; }\n"
    )
    assert undefined_reads(check(parse_shader(shader, "GLSL"))) == []


def test_a_global_read_in_a_callee_names_the_calls_from_mainimage(make_shader):
    helpers = (
        GLOBAL + "float inner() { return g; }\n"  # line 2
        "float outer() { return inner() + 1.0; }\n"  # line 3
    )
    shader = make_shader(
        helpers + "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "fragColor = vec4(outer());\n}\n"  # line 6
    )
    (u,) = undefined_reads(check(parse_shader(shader, "Image")))
    assert (u.loc.line, u.loc.column) == (2, 24)  # the read, in inner
    assert u.origin.loc.line == 1 and u.symbol.name == "g"
    assert "through outer (line 6) -> inner (line 3)" in u.message
    assert "declared at line 1 without an initializer" in u.message
