"""The AST lint rules beyond their snapshots: the reference lab is clean, the engine builds the
tree and model they read, and the shared analysis (glslcheck/analysis) they rely on."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from glslcheck.frontend import syntax as A
from glslcheck.frontend.parser import parse_units
from glslcheck.lint import engine, lint_paths, lint_source
from glslcheck.lint.config import LintConfig
from glslcheck.lint.rules import all_rules
from glslcheck.semantics import check
from glslcheck.semantics.analysis import FunctionFacts, ignored_parameters
from glslcheck.shadertoy.sources import Shader, Source, find_shaders

from .conftest import REPO_ROOT

LAB = REPO_ROOT / "lab_shaders"
CORPUS = REPO_ROOT / "tests" / "corpus"
AST_RULES = [r.name for r in all_rules().values() if r.needs == "ast"]
HEADER = (
    "// Image.glsl: a test\n// Contributors: Ana: all\n// starter framework by Daniel S. "
    "Buckstein\n"
)


def _findings(text: str, select: list[str] | None = None, *, only: bool = False):
    """The findings of `select`'s rules; with `only`, the other rules do not run at all."""
    src = Source("Image.glsl", text)
    shader = Shader(tabs={"Image": src}, root=".")
    tree, model = engine.syntax_tree(src, shader)
    assert model is not None, "the snippet must parse and check"
    config = LintConfig(select=frozenset(select)) if only and select else None
    found = lint_source(src, config, shader, tree, model)
    return [f for f in found if select is None or f.rule in select]


def _function(text: str, name: str = "f") -> FunctionFacts:
    model = check(parse_units([Source("Image.glsl", text)]), "Image")
    d = next(
        d for d in model.ast.decls if isinstance(d, A.FunctionDefinition) and d.proto.name == name
    )
    return FunctionFacts(d, model)


def _calls(fn: FunctionFacts, callee: str) -> list[A.Call]:
    return [n for n in fn.nodes if type(n) is A.Call and n.callee == callee]


MAIN = "\nvoid mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor = vec4(0.0); }\n"


# --- the reference lab and the corpus -------------------------------------------------------


def test_reference_lab_has_no_findings():
    result = lint_paths([LAB])
    assert result.files == 34
    assert [f"{f.path}:{f.loc.line}: {f.rule}" for f in result.findings] == []


def test_every_lab_file_gets_a_tree_and_model():
    for shader in find_shaders([str(LAB)]):
        for source in shader.sources():
            tree, model = engine.syntax_tree(source, shader)
            assert model is not None and tree is model.ast, source.path


@pytest.mark.parametrize("path", sorted(CORPUS.iterdir()), ids=lambda p: p.name)
def test_ast_rules_run_on_the_corpus(path: Path):
    result = lint_paths([path], {"select": AST_RULES})
    assert result.files == 1
    for f in result.findings:
        assert f.loc.path == str(path) or Path(f.loc.path).resolve() == path.resolve()
        assert f.help


def test_corpus_phong_scene_findings():
    found = {
        (f.rule, f.loc.line)
        for f in lint_paths([CORPUS / "spheres_phong.glsl"], {"select": AST_RULES}).findings
    }
    # lights[2] is animated with iTime in mainImage (allowed); hitSphere returns early: no select
    assert not any(rule == "uniform-outside-mainimage" for rule, _ in found)
    assert ("unguarded-sqrt", 26) in found  # sqrt(h) after `if (h < 0.0) return`: a note only


# --- the engine builds what AST rules read --------------------------------------------------


def test_common_is_linted_inside_the_image_pass(tmp_path: Path):
    # iDate is declared in the Common tab too (iTime there is a compile error, check's to report)
    (tmp_path / "Common.glsl").write_text(
        HEADER + "float helper(in float x) { return x * iDate.w; }\n"
    )
    (tmp_path / "Image.glsl").write_text(
        HEADER + "void mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor = "
        "vec4(helper(1.0)); }\n"
    )
    result = lint_paths([tmp_path], {"select": ["uniform-outside-mainimage", "unused-function"]})
    assert [(Path(f.path).name, f.loc.line, f.rule) for f in result.findings] == [
        ("Common.glsl", 4, "uniform-outside-mainimage")
    ]


def test_a_file_that_does_not_check_gets_text_rules_only(tmp_path: Path):
    p = tmp_path / "Image.glsl"
    p.write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor = pow(x, 2.0); }\n"
    )
    src = Source(str(p), p.read_text())
    shader = find_shaders([str(p)])[0]
    assert engine.syntax_tree(src, shader) == (None, None)
    rules = {f.rule for f in lint_paths([p]).findings}
    assert "missing-header" in rules and "pow-small-exponent" not in rules


def test_ast_findings_are_suppressed_like_any_other():
    text = (
        HEADER + "float f(in float x)\n{\n    return pow(x, 2.0); // glslcheck: "
        "ignore[pow-small-exponent]\n}\n" + MAIN
    )
    assert _findings(text, ["pow-small-exponent", "unused-suppression"]) == []


# --- rule details worth pinning ------------------------------------------------------------


def test_shadowing_local_is_not_a_uniform():
    text = "float f(in float t)\n{\n    float iTime = t;\n    return iTime;\n}\n" + MAIN
    assert _findings(text, ["uniform-outside-mainimage"]) == []


def test_branch_replaceable_help_is_valid_glsl():
    text = (
        "float f(in float a, in float b, in float x)\n{\n"
        "    float m = a > b ? a : b;\n"
        "    float c = x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x);\n"
        "    float s = x < 0.5 ? 2.0 : a;\n"
        "    return m + c + s;\n}\n" + MAIN
    )
    found = _findings(text, ["branch-replaceable"])
    helps = [f.help.removeprefix("write ") for f in found]
    assert helps == ["max(a, b)", "clamp(x, 0.0, 1.0)", "mix(2.0, a, step(0.5, x))"]
    # each replacement checks as a float expression with the same variables
    for h in helps:
        check(
            parse_units(
                [Source("t.glsl", f"float g(float a, float b, float x) {{ return {h}; }}" + MAIN)]
            )
        )


def test_faceforward_replacement_computes_what_the_branch_computes(gl, make_shader):
    """The help's faceforward() gives the branch's vector for every direction, the ones
    perpendicular to the normal (dot exactly 0) included, as the GL driver computes both."""
    from glslcheck.backends.gl import compile_gl

    branch = "dot(d, n) < 0.0 ? n : -n"
    text = f"vec3 f(in vec3 d, in vec3 n)\n{{\n    return {branch};\n}}\n" + MAIN
    (finding,) = _findings(text, ["branch-replaceable"])
    replacement = finding.help.removeprefix("write ")
    assert replacement.startswith("faceforward(")
    # one direction per pixel: x and y in -2..2 by halves, some perpendicular to n = (1, 0, 0)
    image = (
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "    vec3 n = vec3(1.0, 0.0, 0.0);\n"
        "    vec3 d = vec3(floor(fragCoord) * 0.5 - 2.0, -1.0);\n"
        f"    vec3 a = {branch};\n    vec3 b = {replacement};\n"
        "    fragColor = vec4(abs(a - b), dot(d, n) == 0.0 ? 1.0 : 0.5);\n}\n"
    )
    pixels = compile_gl(make_shader(image), gl).render(size=(9, 9))
    assert (pixels[..., 3] == 1.0).any()  # perpendicular directions were tried
    assert not pixels[..., :3].any()


def test_shared_call_and_parity_replacements_compute_what_the_branches_compute(gl, make_shader):
    """The help's statement for arms sharing a cos() (a checkerboard's parity, negative cells
    included) and for an int parity choosing a mix's direction gives each branch's value, as the
    GL driver computes both."""
    from glslcheck.backends.gl import compile_gl

    checker = "    vec2 cell = floor(coord / 2.0);\n    float parity = mod(cell.x + cell.y, 2.0);\n"
    checker_branch = (
        "    if (parity == 0.0) { return 0.5 + 0.5 * cos(8.0 * t + vec3(0.0, 2.0, 4.0)); }\n"
        "    else { return 0.5 + 0.5 * cos(8.0 * t - vec3(4.0, 2.0, 0.0)); }\n"
    )
    fade_branch = (
        "    if (int(cycles) % 2 == 0) { return mix(a, b, t - cycles); }\n"
        "    else { return mix(b, a, t - cycles); }\n"
    )
    functions = (
        f"vec3 checker(in vec2 coord, in float t)\n{{\n{checker}{checker_branch}}}\n"
        "vec3 fade(in vec3 a, in vec3 b, in float t)\n{\n    float cycles = floor(t);\n"
        f"{fade_branch}}}\n"
    )
    found = _findings(functions + MAIN, ["branch-replaceable"])
    assert [f.loc.line for f in found] == [5, 11]
    checker_help, fade_help = (f.help.removeprefix("write ") for f in found)
    assert "cos(mix(" in checker_help and "& 1" in fade_help
    image = (
        functions
        + f"vec3 checker2(in vec2 coord, in float t)\n{{\n{checker}    {checker_help}\n}}\n"
        "vec3 fade2(in vec3 a, in vec3 b, in float t)\n{\n    float cycles = floor(t);\n"
        f"    {fade_help}\n}}\n"
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "    vec2 coord = floor(fragCoord) - 4.0;\n"
        "    float t = 0.37 + coord.x * 0.5;\n"
        "    vec3 a = vec3(0.1, 0.7, 0.3), b = vec3(0.9, 0.2, 0.5);\n"
        "    vec3 d1 = abs(checker(coord, t) - checker2(coord, t));\n"
        "    vec3 d2 = abs(fade(a, b, abs(t)) - fade2(a, b, abs(t)));\n"
        "    vec3 d = max(d1, d2);\n"
        "    vec2 cell = floor(coord / 2.0);\n"
        "    fragColor = vec4(max(d.x, max(d.y, d.z)), mod(floor(abs(t)), 2.0),\n"
        "                     mod(cell.x + cell.y, 2.0), 1.0);\n}\n"
    )
    pixels = compile_gl(make_shader(image), gl).render(size=(9, 9))
    # both parities of the cycles and of the checker's cells were tried
    assert set(np.unique(pixels[..., 1])) == set(np.unique(pixels[..., 2])) == {0.0, 1.0}
    # mix(x, y, s) with s exactly 0.0 or 1.0 is x or y up to the rounding of x + (y - x) * s
    # (one or two roundings of values in [0, 1]: within 2 ulp of 1.0, 2.4e-7)
    assert pixels[..., 0].max() <= 2.4e-7


def test_a_repetition_inside_loop_invariant_work_is_left_to_loop_invariant():
    text = (
        "float f(in vec2 p, in float w)\n{\n    float s = 0.0;\n"
        "    for (int i = 0; i < 4; ++i)\n    {\n"
        "        float u = (p.x + sin(dot(p, p))) / w;\n"
        "        float v = (p.y + sin(dot(p, p))) / w;\n"
        "        s += u * v + float(i);\n    }\n    return s + sin(dot(p, p));\n}\n" + MAIN
    )
    both = _findings(text, ["loop-invariant", "repeated-expression"])
    assert [(f.rule, f.loc.line) for f in both] == [("loop-invariant", 6)]
    assert "(line 6) and" in both[0].message and "(line 7)" in both[0].message
    # alone, repeated-expression reports the repetition; computed once before the loop too, it
    # is still the loop-invariant work (hoisted, it is that value, reused); computed twice
    # outside the hoisted expressions, it is a repetition of its own beside loop-invariant
    assert [f.loc.line for f in _findings(text, ["repeated-expression"], only=True)] == [7]
    before = text.replace("float s = 0.0;", "float s = (p.x + sin(dot(p, p))) / w;").replace(
        "return s + sin(dot(p, p));", "return s;"
    )
    assert [f.rule for f in _findings(before, ["loop-invariant", "repeated-expression"])] == [
        "loop-invariant"
    ]
    twice = before.replace(
        "float s = (p.x + sin(dot(p, p))) / w;",
        "float s = (p.x + sin(dot(p, p))) / w;\n    s += (p.x + sin(dot(p, p))) / w;",
    )
    assert twice != before
    assert {f.rule for f in _findings(twice, ["loop-invariant", "repeated-expression"])} == {
        "loop-invariant",
        "repeated-expression",
    }


def test_length_comparison_flips_the_operator_for_a_right_hand_length():
    text = "float f(in vec2 v, in float r)\n{\n    return float(r > length(v));\n}\n" + MAIN
    (finding,) = _findings(text, ["length-comparison"])
    assert finding.help.endswith("dot(v, v) < r * r")


def test_repeated_expression_message_names_the_first_line():
    text = (
        "vec3 f(in vec3 ro, in vec3 rd, in float t)\n{\n    vec3 a = ro + t * rd;\n"
        "    vec3 b = (ro + t * rd) * 2.0;\n    return a + b;\n}\n" + MAIN
    )
    (finding,) = _findings(text, ["repeated-expression"])
    assert (
        finding.loc.line == 4 and "lines 3 and 4" in finding.message and "reuse 'a'" in finding.help
    )


# --- analysis: keys, dominance, sign analysis ----------------------------------------------


def test_keys_compare_variables_by_declaration():
    fn = _function(
        "float f(in float x)\n{\n    float a = x * 2.0 + 1.0;\n    {\n        float x = 3.0;\n"
        "        a += x * 2.0 + 1.0;\n    }\n    return a + (x * 2.0 + 1.0);\n}\n" + MAIN
    )
    sums = [
        n
        for n in fn.nodes
        if type(n) is A.Binary and n.op == "+" and type(n.right) is A.FloatLiteral
    ]
    assert len(sums) == 3
    assert fn.key(sums[0]) == fn.key(sums[2]) != fn.key(sums[1])


def test_dominance_of_branches_and_loops():
    fn = _function(
        "float f(in float x, in bool c)\n{\n    float s = sin(x);\n"
        "    if (c) { s += sin(x); } else { s -= sin(x); }\n"
        "    for (int i = 0; i < 2; ++i) { s += sin(x); }\n    return s + sin(x);\n}\n" + MAIN
    )
    first, then_, else_, loop, last = _calls(fn, "sin")
    assert fn.dominates(first, then_) and fn.dominates(first, loop) and fn.dominates(first, last)
    assert not fn.dominates(then_, else_) and not fn.dominates(then_, last)
    assert not fn.dominates(loop, last)


@pytest.mark.parametrize(
    "expr, negative",
    [
        ("dot(n, l)", True),
        ("max(dot(n, l), 0.0)", False),
        ("clamp(dot(n, l), 0.0, 1.0)", False),
        ("1.0 - max(dot(n, l), 0.0)", False),
        ("1.0 - x", True),
        ("x", False),  # a parameter of unknown sign: no witness
        ("-x", True),
        ("x * x", False),
        ("abs(x) + length(n)", False),
        ("sin(x) * 0.5 + 0.5", False),
        ("sin(x)", True),
        ("dot(n, n)", False),
        ("reflect(-l, n).x", True),
        ("-2.0", True),
        ("iTime * 0.5", False),
        ("smoothstep(0.0, 1.0, x) - 0.5", True),
        ("mix(0.2, 0.8, fract(x))", False),
    ],
)
def test_sign_analysis(expr: str, negative: bool):
    fn = _function(
        f"float f(in vec3 n, in vec3 l, in float x)\n{{\n    return {expr};\n}}\n" + MAIN
    )
    ret = next(n for n in fn.nodes if type(n) is A.Return)
    assert (fn.negative_witness(ret.value) is not None) == negative


def test_sign_analysis_follows_the_last_assignment_on_every_path():
    fn = _function(
        "float f(in vec3 n, in vec3 l, in bool c)\n{\n    float k = dot(n, l);\n"
        "    float a = pow(k, 2.5);\n    k = max(k, 0.0);\n    float b = pow(k, 2.5);\n"
        "    float m = dot(n, l);\n    if (c) { m = 1.0; }\n    return a + b + pow(m, 2.5);\n}\n"
        + MAIN
    )
    bases = [c.args[0] for c in _calls(fn, "pow")]
    assert [fn.negative_witness(b) is not None for b in bases] == [True, False, False]


def test_one_answer_for_lvalues_and_call_targets():
    from glslcheck.language.builtin_functions import Overload
    from glslcheck.semantics.analysis import param_directions, written_variable
    from glslcheck.semantics.model import Constructor, Symbol

    fn = _function(
        "struct S { vec3 p[2]; };\n"
        "void g(in float a, out vec3 b, inout int c) { b = vec3(a); c += 1; }\n"
        "void f() { S s; vec3 v; int k = 0; v.x = 1.0; s.p[k].y = 2.0; g(1.0, v, k);"
        " float m = modf(1.5, v.z); v = vec3(m); }" + MAIN
    )
    model = fn.model
    targets = [n.target for n in fn.nodes if type(n) is A.Assignment]
    assert [
        (written_variable(model, t)[0].name, written_variable(model, t)[1]) for t in targets
    ] == [("v", False), ("s", False), ("v", True)]
    (g,) = _calls(fn, "g")
    (modf,) = _calls(fn, "modf")
    (vec3,) = [n for n in _calls(fn, "vec3")]
    assert isinstance(model.call_target(g), Symbol) and param_directions(model.call_target(g)) == [
        "in",
        "out",
        "inout",
    ]
    assert isinstance(model.call_target(modf), Overload) and param_directions(
        model.call_target(modf)
    ) == ["in", "out"]
    target = model.call_target(vec3)
    assert (
        isinstance(target, Constructor)
        and str(target.type) == "vec3"
        and param_directions(target) == []
    )
    # the writes the analysis records come from the same two answers: v by g's out and modf's out
    v = written_variable(model, targets[0])[0]
    assert [w.kind for w in fn.writes_to(v)] == ["decl", "part", "out", "out", "="]


_HIT_BODIES = [
    # the record's fields are filled in on the function's own copy: never in the result
    "if (t < 0.0) { return false; }\n    rec.t = t;\n    rec.p = o + t * rec.p;\n    return true;",
    # a condition reads the record
    "if (rec.t < t) { return false; }\n    return true;",
    # the record reaches the returned value through a local
    "float s = rec.t * 2.0;\n    return s > t;",
    # a loop's bound reads the point: the writes of every iteration depend on it
    "bool h = false;\n    for (float u = 0.0; u < o.x; u += 1.0) { h = !h; }\n    return h;",
]


@pytest.mark.parametrize("body", _HIT_BODIES)
def test_ignored_parameters_are_those_the_result_never_changes_with(body, gl, make_shader):
    """The parameters a pure function's result is said to ignore are those whose argument,
    changed, changes no result the GL driver computes over a grid of the others' values (both
    signs of t and of rec.t, o.x from 0 to 4)."""
    from glslcheck.backends.gl import compile_gl

    function = (
        "struct Rec { float t; vec3 p; };\n"
        f"bool f(in float t, in Rec rec, in vec3 o)\n{{\n    {body}\n}}\n"
    )
    fn = _function(function + MAIN)
    ignored = ignored_parameters(fn.model, fn.symbol)
    image = function + (
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "    vec2 c = floor(fragCoord) * 0.5 - 2.0;\n"
        "    float t = c.x;\n    Rec rec = Rec(c.y, vec3(c, 1.0));\n"
        "    vec3 o = vec3(c + 2.0, 0.5);\n"
        "    bool base = f(t, rec, o);\n"
        "    fragColor = vec4(f(t + 1.5, rec, o) != base ? 1.0 : 0.0,\n"
        "                     f(t, Rec(rec.t + 1.5, rec.p + 1.5), o) != base ? 1.0 : 0.0,\n"
        "                     f(t, rec, o + 1.0) != base ? 1.0 : 0.0, 1.0);\n}\n"
    )
    pixels = compile_gl(make_shader(image), gl).render(size=(9, 9))
    changes = {i for i in range(3) if pixels[..., i].any()}
    assert set(ignored) == set(range(3)) - changes
