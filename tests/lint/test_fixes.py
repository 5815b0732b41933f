"""The fixes rules offer (glslcheck/lint/fixes): each rule's rewrite made by the fixer and checked
by linting the result again (the rule is gone, the file still compiles, no other rule fires on
the lines it changed), edits applied and followed, files read and written keeping their bytes.
Rendering before and after is tests/verify/test_fix_proof.py's."""

from __future__ import annotations

import random

import pytest

from glslcheck.lint import lint_paths
from glslcheck.lint.fixes import Edit, Fix
from glslcheck.lint.fixes.edits import EditError, apply_edits, apply_fixes, position_map
from glslcheck.lint.fixes.files import FileText, read_file, to_bytes, unified_diff, write_file
from glslcheck.shadertoy.sources import decode

HEADER = "// Image.glsl: a test shader for one fix\n// Contributors: Ana Ruiz: all of it\n"


def findings(path):
    return lint_paths([str(path)]).findings


def fix_of(path, rule):
    offered = [f for f in findings(path) if f.rule == rule]
    assert offered, f"{rule} does not report {path.read_text()}"
    assert offered[0].fix is not None, f"{rule} offers no fix"
    return offered[0], offered[0].fix


def fixed(tmp_path, body: str, rule: str, name="Image.glsl"):
    """Lint `body`, make the rule's first fix, lint again: (the fix, the new text, findings)."""
    path = tmp_path / name
    path.write_text(HEADER + body)
    before = findings(path)
    _, fix = fix_of(path, rule)
    new = apply_fixes(path.read_text(), [fix])
    path.write_text(new)
    after = findings(path)
    assert not [f for f in after if f.rule == "compile-error"], new
    assert len([f for f in after if f.rule == rule]) < len([f for f in before if f.rule == rule])
    return fix, new, before, after


CASES = {
    "pow-small-exponent": (
        """// shade by distance
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float d = length(fragCoord / iResolution.xy); // distance from the corner
    float k = 1.0 / (1.0 + pow(d, 2.0)); // the falloff
    fragColor = vec4(vec3(k), 1.0); // grey
}
""",
        "d * d",
    ),
    "length-comparison": (
        """// a disc
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.y; // square pixels
    float inside = length(uv - vec2(0.8, 0.5)) < 0.3 ? 1.0 : 0.0; // in the disc
    fragColor = vec4(vec3(inside), 1.0); // white disc
}
""",
        "dot(",
    ),
    "sqrt-comparison": (
        """// a disc from a squared length
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 p = fragCoord / iResolution.y - vec2(0.8, 0.5); // from the centre
    float inside = sqrt(dot(p, p)) < 0.3 ? 1.0 : 0.0; // in the disc
    fragColor = vec4(vec3(inside), 1.0); // white disc
}
""",
        "0.09",
    ),
    "repeated-expression": (
        """// a wave
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy; // 0..1
    float a = sin(uv.x * 6.0) * 0.5 + 0.5; // red wave
    float b = sin(uv.x * 6.0) * 0.25 + 0.5; // green wave
    fragColor = vec4(a, b, 0.0, 1.0); // both
}
""",
        "= sin(uv.x * 6.0);",
    ),
    "loop-invariant": (
        """// three bands
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy; // 0..1
    float sum = 0.0; // the bands so far
    for (int i = 0; i < 3; ++i)
    {
        sum += float(i) * sin(uv.x * 3.0 + uv.y); // one band
    }
    fragColor = vec4(vec3(sum / 3.0), 1.0); // grey
}
""",
        "= sin(uv.x * 3.0 + uv.y);",
    ),
}


@pytest.mark.parametrize("rule", sorted(CASES))
def test_a_rules_fix_removes_its_finding_and_compiles(tmp_path, rule):
    body, wanted = CASES[rule]
    fix, new, before, after = fixed(tmp_path, body, rule)
    assert wanted in new
    assert fix.applicability == "safe"
    # nothing but a comment for an added line is new: compare the other rules' counts
    for r in {f.rule for f in after} - {"missing-comment"}:
        assert sum(f.rule == r for f in after) <= sum(f.rule == r for f in before), r


def test_one_pow_finding_per_line_rewrites_every_call_of_it(tmp_path):
    body = """// a ring
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 p = fragCoord / iResolution.xy - 0.5; // centred
    float r = pow(p.x, 2.0) + pow(p.y, 2.0) + pow(p.x + p.y, 2.0); // squared sizes
    fragColor = vec4(vec3(r), 1.0); // grey
}
"""
    fix, new, before, after = fixed(tmp_path, body, "pow-small-exponent")
    assert sum(f.rule == "pow-small-exponent" for f in before) == 1
    assert not [f for f in after if f.rule == "pow-small-exponent"]
    assert "pow(" not in new and "p.x * p.x + p.y * p.y" in new


def test_the_uniform_fix_passes_the_uniform_down_every_call_chain(tmp_path):
    body = """// a pulse
float pulse(in float x) // how bright at x
{
    return 0.5 + 0.5 * sin(x * 10.0 - iTime); // travels with time
}
vec3 shade(in vec2 uv) // colour of a pixel
{
    return vec3(pulse(uv.x), pulse(uv.y), 0.0); // two pulses
}
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(shade(fragCoord / iResolution.xy), 1.0); // opaque
}
"""
    fix, new, before, after = fixed(tmp_path, body, "uniform-outside-mainimage")
    assert not [f for f in after if f.rule == "uniform-outside-mainimage"]
    # every call of pulse passes shade's new parameter, mainImage passes the uniform
    assert new.count(", time)") == 2 and "iTime)" in new.split("mainImage")[1]
    assert "// travels with time" in new and "// two pulses" in new


def test_a_fix_keeps_the_comments_and_indentation_around_it(tmp_path):
    body = CASES["repeated-expression"][0].replace("    ", "\t")
    _, new, _, _ = fixed(tmp_path, body, "repeated-expression")
    old_lines = (HEADER + body).split("\n")
    for line in old_lines:  # each comment is still there, on a line indented as it was
        if "//" in line:
            comment = line[line.index("//") :]
            assert any(n.endswith(comment) for n in new.split("\n")), comment
    added = [n for n in new.split("\n") if n not in old_lines and "sin(" in n]
    assert added and all(n.startswith("\t") and "//" not in n for n in added)


def test_the_header_template_names_the_file_and_is_never_safe(tmp_path):
    path = tmp_path / "Image.glsl"
    path.write_text("void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n")
    _, fix = fix_of(path, "missing-header")
    assert fix.applicability == "unsafe" and fix.why
    new = apply_fixes(path.read_text(), [fix])
    assert new.startswith("// Image.glsl:\n")
    path.write_text(new)  # the rule still asks for the fields the student fills in
    assert [f for f in findings(path) if f.rule == "missing-header"]
    filled = new.replace("// Image.glsl:", "// Image.glsl: paints the screen white", 1)
    filled = filled.replace("// Contributors:", "// Contributors: Ana Ruiz: all of it", 1)
    path.write_text(filled)  # once filled in, the header is complete
    assert not [f for f in findings(path) if f.rule == "missing-header"]


def test_a_comparison_with_a_bound_that_may_be_negative_is_an_unsafe_fix(tmp_path):
    path = tmp_path / "Image.glsl"
    path.write_text(
        HEADER
        + """// a disc of a varying radius
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 p = fragCoord / iResolution.y; // square pixels
    float r = p.x - 0.5; // radius, negative on the left
    fragColor = vec4(length(p) < r ? 1.0 : 0.0); // the disc
}
"""
    )
    _, fix = fix_of(path, "length-comparison")
    assert fix.applicability == "unsafe" and "negative" in fix.why


def test_a_node_from_a_macro_gets_no_fix(tmp_path):
    path = tmp_path / "Image.glsl"
    path.write_text(
        HEADER
        + """#define SQ(x) pow(x, 2.0)
// squares
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float d = length(fragCoord); // distance
    fragColor = vec4(SQ(d)); // squared
}
"""
    )
    offered = [f for f in findings(path) if f.rule == "pow-small-exponent"]
    assert offered and all(f.fix is None for f in offered)


# --- edits --------------------------------------------------------------------------------


def test_overlapping_edits_are_refused():
    text = "abcdef\n"
    with pytest.raises(EditError):
        apply_edits(text, [Edit(1, 2, 1, 5, "X"), Edit(1, 3, 1, 4, "Y")])
    f1 = Fix("a", "p", (Edit(1, 2, 1, 5, "X"),))
    f2 = Fix("b", "p", (Edit(1, 4, 1, 6, "Y"),))
    assert f1.overlaps(f2) and not f1.overlaps(Fix("c", "p", (Edit(1, 5, 1, 5, "Z"),)))


def test_items_inserted_into_an_empty_list_are_joined():
    text = "f();\n"
    new = apply_edits(text, [Edit(1, 3, 1, 3, "a", item=True), Edit(1, 3, 1, 3, "b", item=True)])
    assert new == "f(" + ", ".join(["a", "b"]) + ");\n"


def test_positions_follow_the_edits():
    """Every character outside a replaced span is found again where position_map says."""
    rng = random.Random(7)
    text = "".join(rng.choice("ab \n") for _ in range(400)) + "\n"
    lines = text.split("\n")
    for _ in range(50):
        edits, taken = [], []
        for _ in range(rng.randint(1, 6)):
            line = rng.randint(1, len(lines))
            c0 = rng.randint(1, len(lines[line - 1]) + 1)
            c1 = rng.randint(c0, len(lines[line - 1]) + 1)
            if any(line == t[0] and not (c1 <= t[1] or c0 >= t[2]) for t in taken):
                continue
            taken.append((line, c0, c1))
            edits.append(Edit(line, c0, line, c1, rng.choice(["", "X", "YY\n", "\nZ"])))
        new = apply_edits(text, edits)
        where = position_map(text, edits)
        new_lines = new.split("\n")
        for line, body in enumerate(lines, start=1):
            for col, ch in enumerate(body, start=1):
                if any(line == t[0] and t[1] <= col < t[2] for t in taken):
                    continue
                nl, nc = where(line, col)
                assert new_lines[nl - 1][nc - 1] == ch


# --- files --------------------------------------------------------------------------------


def test_crlf_line_endings_and_the_bom_are_kept(tmp_path):
    path = tmp_path / "Image.glsl"
    body = CASES["repeated-expression"][0]
    path.write_bytes(b"\xef\xbb\xbf" + (HEADER + body).replace("\n", "\r\n").encode())
    original = read_file(str(path))
    _, fix = fix_of(path, "repeated-expression")
    new = apply_fixes(original.text, [fix])
    data = to_bytes(original, new)
    assert data.startswith(b"\xef\xbb\xbf")
    assert decode(data, "x") == new
    assert data.count(b"\n") == data.count(b"\r\n") == new.count("\n")


def test_mixed_line_endings_are_kept_line_by_line():
    data = b"a\r\nb\nc\r\n"
    original = FileText("p", data, decode(data, "p"))
    assert to_bytes(original, "a\nnew\nb\nc\n") == b"a\r\nnew\r\nb\nc\r\n"


def test_a_file_changed_on_disk_is_left_alone(tmp_path):
    path = tmp_path / "Image.glsl"
    path.write_text("float a;\n")
    original = read_file(str(path))
    path.write_text("float b;\n")
    assert "changed on disk" in write_file(original, "float c;\n")
    assert path.read_text() == "float b;\n"


def test_write_keeps_the_mode(tmp_path):
    path = tmp_path / "Image.glsl"
    path.write_text("float a;\n")
    path.chmod(0o640)
    assert write_file(read_file(str(path)), "float c;\n") is None
    assert path.read_text() == "float c;\n" and path.stat().st_mode & 0o777 == 0o640


def test_the_diff_applies_back_to_the_new_text(tmp_path):
    """The unified diff's lines rebuild the new text from the old (a second computation)."""
    old = "".join(f"line {i}\n" for i in range(30)) + "}\n"
    new = old.replace("line 3\n", "line three\nadded\n").replace("line 28\n", "")
    diff = unified_diff(FileText("p", old.encode(), old), new)
    out, src = [], old.split("\n")[:-1]
    pos = 0
    for line in diff.split("\n")[2:-1]:
        if line.startswith("@@"):
            first = int(line.split()[1].split(",")[0][1:])
            out.extend(src[pos : first - 1])
            pos = first - 1
        elif line.startswith("-"):
            pos += 1
        elif line.startswith("+"):
            out.append(line[1:])
        else:
            out.append(src[pos])
            pos += 1
    out.extend(src[pos:])
    assert "\n".join(out) + "\n" == new


def test_the_json_report_carries_the_fix_edits(tmp_path):
    """The edits in the JSON report rebuild the text the fixer makes."""
    import json

    from glslcheck.lint.report import render

    path = tmp_path / "Image.glsl"
    path.write_text(HEADER + CASES["loop-invariant"][0])
    result = lint_paths([str(path)])
    finding = next(f for f in result.findings if f.rule == "loop-invariant")
    record = next(
        r for r in json.loads(render(result, "json"))["findings"] if r["rule"] == "loop-invariant"
    )
    assert record["fix"]["applicability"] == "safe"
    edits = [Edit(**e) for e in record["fix"]["edits"]]
    assert apply_edits(path.read_text(), edits) == apply_fixes(path.read_text(), [finding.fix])


def test_a_local_is_never_declared_inside_a_block_comment(tmp_path):
    """The first computation's statement follows the last line of a block comment opened after
    code: the local goes on the statement's line, not into the comment."""
    body = CASES["repeated-expression"][0].replace(
        "// 0..1\n", "/* 0..1,\n       across the screen */\n"
    )
    fix, new, _, _ = fixed(tmp_path, body, "repeated-expression")
    assert "/* 0..1,\n       across the screen */\n" in new


def test_grouping_parentheses_go_with_the_value_a_call_s_stay(tmp_path):
    body = """// distance to a light, twice
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy; // 0..1
    float x = (uv - vec2(0.5, 0.2)).x; // across
    float d = dot((uv - vec2(0.5, 0.2)), uv); // along
    fragColor = vec4(x, d, 0.0, 1.0); // both
}
"""
    fix, new, _, _ = fixed(tmp_path, body, "repeated-expression")
    name = fix.title.split("'")[1]
    assert f"float x = {name}.x;" in new and f"dot({name}, uv)" in new


def test_the_sarif_report_carries_the_fix_as_replacements(tmp_path):
    """SARIF `fixes`: the replacements rebuild the text the fixer makes."""
    import json

    from glslcheck.lint.report import render

    path = tmp_path / "Image.glsl"
    path.write_text(HEADER + CASES["repeated-expression"][0])
    result = lint_paths([str(path)])
    finding = next(f for f in result.findings if f.rule == "repeated-expression")
    doc = json.loads(render(result, "sarif"))
    entry = next(r for r in doc["runs"][0]["results"] if r["ruleId"] == "repeated-expression")
    (change,) = entry["fixes"][0]["artifactChanges"]
    edits = [
        Edit(
            r["deletedRegion"]["startLine"],
            r["deletedRegion"]["startColumn"],
            r["deletedRegion"]["endLine"],
            r["deletedRegion"]["endColumn"],
            r["insertedContent"]["text"],
        )
        for r in change["replacements"]
    ]
    assert apply_edits(path.read_text(), edits) == apply_fixes(path.read_text(), [finding.fix])


def test_the_text_report_shows_each_fix_and_the_command(tmp_path):
    from glslcheck.lint.report import render

    path = tmp_path / "Image.glsl"
    path.write_text(HEADER + CASES["loop-invariant"][0])
    result = lint_paths([str(path)])
    text = render(result, "text")
    finding = next(f for f in result.findings if f.rule == "loop-invariant")
    assert f"  fix (safe): {finding.fix.title}" in text
    safe = sum(1 for f in result.findings if f.fix is not None and f.fix.applicability == "safe")
    assert (
        f"{safe} finding{'s' if safe != 1 else ''} with a safe fix: `glslcheck lint --fix`" in text
    )
    assert text.rstrip().split("\n")[-1].startswith(f"{len(result.findings)} finding")


def test_a_file_that_cannot_be_written_is_reported_not_raised(tmp_path, monkeypatch):
    """A write error (a read-only folder, a full disk: made here by the writer failing) is the
    file's message; the run goes on with the other files."""
    import contextlib

    from glslcheck.base import images
    from glslcheck.base.diagnostics import InputError

    @contextlib.contextmanager
    def failing(path, what="file"):
        raise InputError(f"{path}: error: cannot write the {what} (permission denied)")
        yield  # pragma: no cover

    path = tmp_path / "Image.glsl"
    path.write_text("float a;\n")
    original = read_file(str(path))
    monkeypatch.setattr(images, "atomic_write", failing)
    problem = write_file(original, "float c;\n")
    assert problem == "cannot write the fixed shader (permission denied); not written"
    assert path.read_text() == "float a;\n"
