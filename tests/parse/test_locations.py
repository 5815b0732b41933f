"""Locations: every node spans its text in the user's file, through macros and the Common tab."""

from __future__ import annotations

import pytest

from glslcheck.base.diagnostics import GlslError
from glslcheck.frontend import syntax as A
from glslcheck.frontend.parser import parse_shader, parse_units
from glslcheck.shadertoy.sources import Source


def _find(tree, cls, pred=lambda n: True):
    return [n for n in tree.walk() if isinstance(n, cls) and pred(n)]


def test_expression_and_statement_spans():
    text = (
        "void mainImage(out vec4 c, in vec2 f)\n"
        "{\n"
        "    vec3 p = vec3(f, 1.0) * 2.0;\n"
        "    c = vec4(p.xy, length(p), 1.0);\n"
        "}\n"
    )
    tree = parse_units([Source("Image.glsl", text)]).ast
    (mul,) = _find(tree, A.Binary, lambda n: n.op == "*")
    assert (mul.loc.line, mul.loc.column, mul.loc.end_line, mul.loc.end_column) == (3, 14, 3, 32)
    (call,) = _find(tree, A.Call, lambda n: n.callee == "length")
    assert (call.loc.line, call.loc.column, call.loc.end_column) == (4, 20, 29)
    (swz,) = _find(tree, A.Field)
    assert (swz.loc.column, swz.loc.end_column) == (14, 18)
    assert (swz.name_loc.column, swz.name_loc.end_column) == (16, 18)
    (decl,) = _find(tree, A.Declarator)
    assert (decl.name_loc.line, decl.name_loc.column) == (3, 10)
    (fn,) = _find(tree, A.FunctionDefinition)
    assert (fn.loc.line, fn.loc.end_line, fn.loc.end_column) == (1, 5, 2)
    assert (fn.proto.name_loc.line, fn.proto.name_loc.column) == (1, 6)


def test_tabs_keep_columns_and_crlf_and_bom(tmp_path):
    (tmp_path / "Image.glsl").write_bytes(
        b"\xef\xbb\xbf// caf\xc3\xa9 \xe2\x80\x94 a non-ASCII comment\r\n"
        b"void mainImage(out vec4 c, in vec2 f)\r\n{\r\n\tc = vec4(1.0);\r\n}\r\n"
    )
    from glslcheck.shadertoy.sources import load_shader

    tree = parse_shader(load_shader(tmp_path / "Image.glsl")).ast
    (assign,) = _find(tree, A.Assignment)
    # A tab counts as one column, as in compilers' messages.
    assert (assign.loc.line, assign.loc.column) == (4, 2)


def test_common_then_image_locations(tmp_path):
    (tmp_path / "Common.glsl").write_text("// shared\nfloat sq(float x) { return x * x; }\n")
    (tmp_path / "Image.glsl").write_text(
        "void mainImage(out vec4 c, in vec2 f)\n{\n    c = vec4(sq(f.x));\n}\n"
    )
    from glslcheck.shadertoy.sources import load_shader

    shader = load_shader(tmp_path)
    tree = parse_shader(shader).ast
    (mul,) = _find(tree, A.Binary)
    assert mul.loc.path.endswith("Common.glsl") and (mul.loc.line, mul.loc.column) == (2, 28)
    (call,) = _find(tree, A.Call, lambda n: n.callee == "sq")
    assert call.loc.path.endswith("Image.glsl") and (call.loc.line, call.loc.column) == (3, 14)


def test_error_in_image_after_common_points_into_image(tmp_path):
    (tmp_path / "Common.glsl").write_text("float sq(float x) { return x * x; }\n")
    (tmp_path / "Image.glsl").write_text(
        "void mainImage(out vec4 c, in vec2 f)\n{\n    c = vec4(sq(f.x))\n}\n"
    )
    from glslcheck.shadertoy.sources import load_shader

    with pytest.raises(GlslError) as info:
        parse_shader(load_shader(tmp_path))
    (d,) = info.value.diagnostics
    assert d.loc.path.endswith("Image.glsl") and (d.loc.line, d.loc.column) == (3, 22)


def test_macro_expansion_points_at_the_macro_use():
    text = (
        "#define SQ(x) ((x) * (x))\n"
        "#define BAD (1.0 + )\n"
        "void mainImage(out vec4 c, in vec2 f)\n"
        "{\n"
        "    float a = SQ(f.x) + 1.0;\n"
        "    c = vec4(a);\n"
        "}\n"
    )
    tree = parse_units([Source("Image.glsl", text)]).ast
    (inner,) = _find(tree, A.Binary, lambda n: n.op == "*")
    # Text that came from SQ(...) maps to the use `SQ(f.x)` on line 5, column 15.
    assert (inner.loc.line, inner.loc.column) == (5, 15)
    (plus,) = _find(tree, A.Binary, lambda n: n.op == "+")
    assert (plus.loc.line, plus.loc.column, plus.loc.end_column) == (5, 15, 28)


def test_syntax_error_inside_macro_expansion_points_at_the_use():
    text = (
        "#define BAD (1.0 + )\n"
        "void mainImage(out vec4 c, in vec2 f)\n"
        "{\n"
        "    float a = BAD;\n"
        "    c = vec4(a);\n"
        "}\n"
    )
    with pytest.raises(GlslError) as info:
        parse_units([Source("Image.glsl", text)])
    (d,) = info.value.diagnostics
    assert (d.loc.line, d.loc.column) == (4, 15)


def _pending_spans(text):
    """The program's nodes with each node's location as the parser left it (computed when first
    read), and the same locations computed now."""
    from glslcheck.base.diagnostics import Location

    result = parse_units([Source("Image.glsl", text)])
    nodes = list(result.ast.walk())
    pending = [type(n.loc) is not Location for n in nodes]
    return result, nodes, pending


def test_a_pending_location_is_the_location_it_stands_for():
    import copy
    import pickle

    from glslcheck.base.diagnostics import Location

    text = "void mainImage(out vec4 c, in vec2 f)\n{\n    c = vec4(f.x * 2.0, f.y, 0.0, 1.0);\n}\n"
    result, nodes, pending = _pending_spans(text)
    assert sum(pending) > 5  # the parser left most of them to be computed when read
    computed = [result.pp.locate_span(*n.loc._pending[1:]) for n, p in zip(nodes, pending) if p]
    locs = [n.loc for n, p in zip(nodes, pending) if p]
    # Each use computes it first: equal both ways, the same hash, repr, str, pickle and copy.
    assert [loc == want for loc, want in zip(locs[0::5], computed[0::5])] == [True] * len(
        locs[0::5]
    )
    assert [want == loc for loc, want in zip(locs[1::5], computed[1::5])] == [True] * len(
        locs[1::5]
    )
    assert [hash(loc) for loc in locs[2::5]] == [hash(want) for want in computed[2::5]]
    assert [repr(loc) for loc in locs[3::5]] == [repr(want) for want in computed[3::5]]
    assert [str(loc) for loc in locs[4::5]] == [str(want) for want in computed[4::5]]
    assert all(type(loc) is Location for loc in locs)  # and each is a plain Location after
    _, nodes, pending = _pending_spans(text)
    locs = [n.loc for n, p in zip(nodes, pending) if p]
    again = [pickle.loads(pickle.dumps(loc)) for loc in locs[:3]] + [
        copy.copy(loc) for loc in locs[3:6]
    ]
    assert all(type(loc) is Location for loc in again)
    assert again == locs[:6]
    assert not hasattr(locs[-1], "other") and {locs[-1]: 1}[locs[-1]] == 1
