"""`glslcheck lint --fix / --diff / --unsafe-fixes` and the proof behind them
(glslcheck/verification/fix_proof.py): a fix is applied only when the rewritten shader renders
as the original did (verify's frame and tolerance, NumPy backend), a fix that changes the
picture is refused with the numbers, files are written only when they still hold what was read,
`--diff` writes nothing. Expected renders come from rendering, never from typed values."""

from __future__ import annotations

import os

import pytest

from glslcheck.cli.main import main
from glslcheck.lint import lint_paths
from glslcheck.lint.fixes import Edit, Fix
from glslcheck.lint.fixes.files import write_file
from glslcheck.lint.rules import pow_small_exponent
from glslcheck.shadertoy.sources import load_shader
from glslcheck.shadertoy.wrapper import DEFAULT_SIZE
from glslcheck.verification.compare import compare
from glslcheck.verification.fix_proof import plan_fixes
from glslcheck.verification.verify import compile_backend, frame_specs

HEADER = "// Image.glsl: a test shader for the fixes\n// Contributors: Ana Ruiz: all of it\n"

# pow-small-exponent, repeated-expression, loop-invariant and uniform-outside-mainimage, each
# with a fix offered as safe
SHADER = (
    HEADER
    + """// the rings of a pulse
float ring(in vec2 p) // one ring's brightness
{
    float d = length(p); // distance from the centre
    return 0.5 + 0.5 * sin(d * 20.0 - iTime); // travels outwards
}
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (fragCoord - 0.5 * iResolution.xy) / iResolution.y; // centred
    float d = 2.0 * length(uv); // twice the distance from the centre
    float k = 1.0 / (1.0 + pow(d, 2.0)); // the falloff
    float glow = 0.0; // summed below
    for (int i = 0; i < 3; ++i)
    {
        glow += float(i) * k * sin(uv.x * 3.0 + uv.y); // one band per step
    }
    float a = sin(uv.x * 6.0) * 0.5 + 0.5; // red wave
    float b = sin(uv.x * 6.0) * 0.25 + 0.5; // green wave
    fragColor = vec4(a * ring(uv), b, glow / 3.0, 1.0); // all of it
}
"""
)


def render(path, channels=None) -> list:
    shader = load_shader(path)
    if channels is not None:
        from glslcheck.shadertoy.sources import Shader

        shader = Shader(tabs=dict(shader.tabs), root=shader.root, channels=channels)
    program = compile_backend(shader, "numpy")
    return [program.render(size=DEFAULT_SIZE, time=s.time, frame=s.frame) for s in frame_specs()]


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def rules_with_fixes(path) -> dict[str, int]:
    out: dict[str, int] = {}
    for f in lint_paths([str(path)]).findings:
        if f.fix is not None and f.fix.applicability == "safe":
            out[f.rule] = out.get(f.rule, 0) + 1
    return out


def test_fix_applies_the_proven_fixes_and_the_picture_stays(workdir, capsys):
    path = workdir / "Image.glsl"
    path.write_text(SHADER)
    offered = rules_with_fixes(path)
    assert set(offered) >= {
        "pow-small-exponent",
        "repeated-expression",
        "loop-invariant",
        "uniform-outside-mainimage",
    }
    before = render(path)
    status = main(["lint", "--fix", "Image.glsl"])
    err = capsys.readouterr().err
    assert path.read_text() != SHADER
    left = {f.rule for f in lint_paths([str(path)]).findings}
    assert not left & set(offered), err
    assert status == (1 if left else 0)
    for old, new in zip(before, render(path)):
        assert compare(old, new).match
    assert "fixed" in err


def test_diff_writes_nothing_and_shows_what_fix_would_write(workdir, capsys):
    path = workdir / "Image.glsl"
    path.write_text(SHADER)
    stat = os.stat(path)
    assert main(["lint", "--diff", "Image.glsl"]) == 1
    diff = capsys.readouterr().out
    assert path.read_text() == SHADER and os.stat(path).st_mtime_ns == stat.st_mtime_ns
    assert diff.startswith("--- Image.glsl\n+++ Image.glsl\n@@ ")
    main(["lint", "--fix", "Image.glsl"])
    capsys.readouterr()
    fixed = path.read_text()
    # every added line of the diff is a line of what --fix wrote, every removed one is gone
    added = [line[1:] for line in diff.split("\n") if line[:1] == "+" and line[:3] != "+++"]
    removed = [line[1:] for line in diff.split("\n") if line[:1] == "-" and line[:3] != "---"]
    assert added and all(line in fixed.split("\n") for line in added)
    assert all(line not in fixed.split("\n") for line in removed)


# Mostly uncommented (more than three quarters of its code lines uncovered): missing-comment
# reads `wave` group by group at its blank line. The repeated-expression fix adds a line, which
# the proof's placeholder comment covers: the file is then no longer mostly uncommented and
# `wave` is one run over its blank line, a line no comment had to explain before or after.
SPARSE = (
    HEADER
    + """
float wave(float x)
{
    float a = x * 2.0;
    float b = a + 1.0;

    float c = b * b;
    return c;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy;
    float r = sin(uv.x * 3.0) + sin(uv.x * 3.0) * uv.y;
    fragColor = vec4(r, wave(uv.y), 0.0, 1.0);
}
"""
)


def test_a_fix_whose_line_makes_a_sparse_file_no_longer_so_is_proven(workdir, capsys):
    path = workdir / "Image.glsl"
    path.write_text(SPARSE)
    assert "repeated-expression" in rules_with_fixes(path)
    before = render(path)
    main(["lint", "--fix", "Image.glsl"])
    err = capsys.readouterr().err
    assert "repeated-expression" not in {f.rule for f in lint_paths([str(path)]).findings}, err
    for old, new in zip(before, render(path)):
        assert compare(old, new).match


def test_diff_of_a_clean_file_exits_0(workdir, capsys):
    path = workdir / "Image.glsl"
    path.write_text(HEADER + "// white\nvoid mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n")
    assert main(["lint", "--diff", "Image.glsl"]) == 0
    assert capsys.readouterr().out == ""


def test_a_fix_that_changes_the_picture_is_refused_with_its_numbers(workdir, monkeypatch):
    """A pow fix made wrong on purpose (x * x * 1.5 for pow(x, 2.0)) and offered as safe."""

    def wrong(ctx, node, e):
        loc = node.loc
        base = ctx.lines[loc.line - 1][
            node.args[0].loc.column - 1 : node.args[0].loc.end_column - 1
        ]
        text = f"({base} * {base} * 1.5)"
        return Fix(
            "a wrong rewrite",
            ctx.path,
            (Edit(loc.line, loc.column, loc.end_line, loc.end_column, text),),
        )

    monkeypatch.setattr(pow_small_exponent, "_fix", wrong)
    path = workdir / "Image.glsl"
    path.write_text(SHADER)
    plans = plan_fixes(lint_paths([str(path)]), {"select": ["pow-small-exponent"]})
    (outcome,) = [o for p in plans for o in p.outcomes if o.rule == "pow-small-exponent"]
    assert not outcome.applied and not outcome.proven
    assert "changes the picture" in outcome.reason
    # the numbers are verify's comparison of the two renders
    rewritten = workdir / "wrong" / "Image.glsl"
    rewritten.parent.mkdir()
    rewritten.write_text(SHADER.replace("pow(d, 2.0)", "(d * d * 1.5)"))
    c = compare(render(path)[0], render(rewritten)[0])
    assert not c.match and f"{c.mismatched_pixels} pixels beyond" in outcome.reason


def test_unsafe_fixes_are_applied_only_when_asked(workdir, capsys):
    path = workdir / "Image.glsl"
    body = SHADER.replace(HEADER, "")  # no header: its fix is a template, never safe
    path.write_text(body)
    main(["lint", "--fix", "Image.glsl"])
    assert "// Image.glsl:" not in path.read_text()
    assert "unsafe" in capsys.readouterr().err
    main(["lint", "--fix", "--unsafe-fixes", "Image.glsl"])
    assert path.read_text().startswith(
        "// the rings of a pulse\n// Image.glsl:\n// Contributors:\n"
    )


def test_fix_keeps_crlf_line_endings(workdir, capsys):
    path = workdir / "Image.glsl"
    path.write_bytes(SHADER.replace("\n", "\r\n").encode())
    main(["lint", "--fix", "Image.glsl"])
    data = path.read_bytes()
    assert data != SHADER.replace("\n", "\r\n").encode()
    assert data.count(b"\n") == data.count(b"\r\n")


def test_a_file_changed_after_the_plan_is_left_alone(workdir):
    path = workdir / "Image.glsl"
    path.write_text(SHADER)
    (plan,) = plan_fixes(lint_paths([str(path)]))
    assert plan.new_text is not None
    path.write_text(SHADER + "// edited meanwhile\n")
    assert "changed on disk" in write_file(plan.original, plan.new_text)
    assert path.read_text() == SHADER + "// edited meanwhile\n"


def test_a_shader_that_does_not_compile_gets_no_fix(workdir, capsys):
    broken = SHADER.replace("glow / 3.0", "glow / 3")  # float / int: a compile error
    path = workdir / "Image.glsl"
    path.write_text(broken)
    main(["lint", "--fix", "Image.glsl"])
    assert path.read_text() == broken
    assert "does not compile" in capsys.readouterr().err


def test_unbound_channels_are_read_as_shadertoy_reads_an_empty_one(workdir, capsys):
    """A student's file without its textures (no channels.json): the proof renders it with the
    channels unbound, says so, and the fixed file renders as the original did that way."""
    from glslcheck.shadertoy.sources import Shader

    textured = SHADER.replace("glow / 3.0", "texture(iChannel0, uv).r")
    path = workdir / "Image.glsl"
    path.write_text(textured)
    original = load_shader(path)
    main(["lint", "--fix", "Image.glsl"])
    assert "iChannels unbound" in capsys.readouterr().err
    assert path.read_text() != textured
    fixed = load_shader(path)
    empty = [Shader(tabs=dict(s.tabs), root=s.root, channels=[]) for s in (original, fixed)]
    programs = [compile_backend(s, "numpy") for s in empty]
    images = [p.render(size=DEFAULT_SIZE, time=0.0, frame=0) for p in programs]
    assert compare(*images).match


def test_fix_with_staged_is_a_usage_error(workdir):
    assert main(["lint", "--fix", "--staged"]) == 2


# the sqrt fixture's bounds are parameters of unknown sign (its fixes are unsafe): a disc instead
DISC = (
    HEADER
    + """// a disc from a squared length
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 p = fragCoord / iResolution.y - vec2(0.8, 0.5); // from the centre
    float inside = sqrt(dot(p, p)) < 0.3 ? 1.0 : 0.0; // in the disc
    fragColor = vec4(vec3(inside), 1.0); // white disc
}
"""
)
RULE_FIXTURES = {
    "normalize-known-length": "normals.glsl",
    "length-comparison": "circles.glsl",
    "sqrt-comparison": DISC,
    "pow-small-exponent": "exponents.glsl",
    "loop-invariant": "loops.glsl",
    "repeated-expression": "repeats.glsl",
    "uniform-outside-mainimage": "uniforms.glsl",
}


@pytest.mark.parametrize("rule", sorted(RULE_FIXTURES))
def test_each_rules_fixes_on_its_fixture_render_as_the_original(workdir, rule):
    """The rule's lint fixture: its fixes applied by --fix are proven, and the fixed text renders
    as the original does (recomputed here from the two texts)."""
    from pathlib import Path

    text = RULE_FIXTURES[rule]
    if "\n" not in text:
        text = (Path(__file__).parent.parent / "lint" / "fixtures" / rule / text).read_text()
    path = workdir / "Image.glsl"
    path.write_text(text)
    plans = plan_fixes(lint_paths([str(path)]), {"select": [rule]})
    applied = [o for p in plans for o in p.outcomes if o.applied]
    assert applied and all(o.proven and o.rule == rule for o in applied)
    (plan,) = plans
    fixed = workdir / "fixed" / "Image.glsl"
    fixed.parent.mkdir()
    fixed.write_text(plan.new_text)
    channels = [] if plan.note else None  # unbound iChannels read as empty ones, as proven
    for old, new in zip(render(path, channels), render(fixed, channels)):
        assert compare(old, new).match
    left = [f for f in lint_paths([str(fixed)]).findings if f.rule == rule]
    assert len(left) == sum(f.rule == rule for f in lint_paths([str(path)]).findings) - sum(
        o.findings for o in applied
    )


def test_the_tabs_of_one_shader_are_fixed_one_after_the_other(workdir, capsys):
    """Common and Image each with a fix: both applied, each proven with the other's fix, and the
    shader renders as before."""
    (workdir / "Common.glsl").write_text(
        """// Common.glsl: shared helpers
// Contributors: Ana Ruiz: all of it
// the squared falloff of a distance
float falloff(in float d)
{
    float a = abs(d); // the distance, whatever its sign
    return 1.0 / (1.0 + pow(a, 2.0)); // inverse square
}
"""
    )
    (workdir / "Image.glsl").write_text(
        """// Image.glsl: a glow
// Contributors: Ana Ruiz: all of it
// shade by distance from the centre
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (fragCoord - 0.5 * iResolution.xy) / iResolution.y; // centred
    float d = length(uv); // distance
    fragColor = vec4(vec3(falloff(d * 4.0)), 1.0) + vec4(vec3(falloff(d * 4.0)) * 0.1, 0.0); // glow
}
"""
    )
    before = render(workdir)
    originals = {n: (workdir / n).read_text() for n in ("Common.glsl", "Image.glsl")}
    main(["lint", "--fix", "Image.glsl", "Common.glsl"])
    capsys.readouterr()
    assert all((workdir / n).read_text() != text for n, text in originals.items())
    left = {f.rule for f in lint_paths([str(workdir)]).findings}
    assert not left & {"pow-small-exponent", "repeated-expression"}
    for old, new in zip(before, render(workdir)):
        assert compare(old, new).match
