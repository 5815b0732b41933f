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
