"""Regression tests for the classes of mistakes the linter made on real student code:
compile errors that silenced the linter, valid code it rejected, the sphere-normal rule decided
by names, repeats counted per repetition, and headers and comments graded unlike a TA. Each
snippet is written in the style of the Fall 2020 GPR-200 submissions (tests/real_lint), not
copied from them."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from glslcheck.lint import lint_paths
from glslcheck.lint.report import render, summary_line
from glslcheck.lint.textscan import inactive_lines

HEADER = (
    "// Image.glsl: a test\n// Contributors: Ana: all\n// starter framework by Daniel S. "
    "Buckstein\n"
)


def _lint(tmp_path: Path, text: str, select: list[str] | None = None, name: str = "Image.glsl"):
    p = tmp_path / name
    p.write_text(text)
    return lint_paths([p], {"select": select} if select else None)


# --- 1. a compile error no longer silences the linter ---------------------------------------


BROKEN = (
    HEADER
    + """
// light position, animated (reads iTime: a course deduction even in a broken function)
vec3 lightAt(in float r)
{
    return vec3(r * cos(iTime), 1.0, undefinedName);
}

// a working function with a repeated value
float twice(in vec3 a, in vec3 b)
{
    return dot(a, b) + dot(a, b);
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(lightAt(twice(vec3(fragCoord, 1.0), vec3(1.0))), 1.0);
}
"""
)


def test_compile_errors_come_first_and_the_rest_is_still_linted(tmp_path: Path):
    result = _lint(tmp_path, BROKEN)
    rules = [(f.rule, f.severity, f.loc.line) for f in result.findings]
    assert rules[0] == ("compile-error", "error", 8)  # 'undefinedName' is not declared
    assert ("uniform-outside-mainimage", "warning", 8) in rules  # read in the broken function
    assert ("repeated-expression", "warning", 14) in rules  # the function that checks
    not_run = [
        f.message for f in result.findings if f.rule == "compile-error" and f.severity == "note"
    ]
    assert "repeated-expression could not run in 'lightAt' (line 6): it does not compile" in not_run
    assert any(m.startswith("unused-function could not run on this file") for m in not_run)
    # one line per rule that could not run, and none for the rule that reads names only
    assert len(not_run) == len({m.split()[0] for m in not_run})
    assert not any(m.startswith("uniform-outside-mainimage") for m in not_run)


def test_text_report_folds_the_rules_that_could_not_run_per_place(tmp_path: Path):
    """The text a student reads names each broken function once, with every rule that skipped
    it; the JSON keeps one record per rule."""
    from glslcheck.lint.report import text_report

    result = _lint(tmp_path, BROKEN)
    notes = [f for f in result.findings if f.rule == "compile-error" and f.severity == "note"]
    text = text_report(result)
    folded = [line for line in text.splitlines() if "could not run" in line]
    assert len(notes) > len(folded) >= 2
    where = next(line for line in folded if "in 'lightAt' (line 6)" in line)
    skipped = [f.message.split()[0] for f in notes if "in 'lightAt' (line 6)" in f.message]
    assert f"{len(skipped)} rules could not run in 'lightAt' (line 6): it does not compile" in where
    assert all(rule in where for rule in skipped)


def test_compile_errors_cost_no_points_and_the_summary_says_so(tmp_path: Path):
    result = _lint(tmp_path, BROKEN)
    error = next(f for f in result.findings if f.severity == "error")
    assert error.penalty == 0
    line = summary_line(result)
    assert "1 compile error, not counted" in line
    assert f"-{result.penalty} point" in line


def test_a_syntax_error_drops_only_its_declaration(tmp_path: Path):
    text = (
        HEADER
        + """
// missing semicolon pasted from Shadertoy
float broken(in float x)
{
    return x * iTime
}

// still linted: the uniform and the repeat
float fine(in float x)
{
    return sin(x * iTime) + sin(x * iTime);
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(broken(fine(fragCoord.x)));
}
"""
    )
    found = [(f.rule, f.severity, f.loc.line) for f in _lint(tmp_path, text).findings]
    assert found[0] == ("compile-error", "error", 8)
    assert ("uniform-outside-mainimage", "warning", 14) in found
    assert ("repeated-expression", "warning", 14) in found
    assert ("compile-error", "error", 20) not in found  # the call of broken() still checks


def test_lint_exit_status_with_a_compile_error(tmp_path: Path):
    p = tmp_path / "Image.glsl"
    p.write_text(BROKEN)
    run = subprocess.run(
        [sys.executable, "-m", "glslcheck", "lint", "--format", "json", str(p)],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 1 and "Traceback" not in run.stderr
    doc = json.loads(run.stdout)
    assert doc["findings"][0]["rule"] == "compile-error"


# --- 2. valid code that was rejected ----------------------------------------------------------


def test_a_struct_name_reused_as_a_parameter_and_a_local(tmp_path: Path):
    text = (
        HEADER
        + """
// a sphere
struct sphere { vec3 center; float radius; };

// whether p is inside: the parameter hides the type inside the function
bool inside(in sphere sphere, in vec3 p)
{
    vec3 d = p - sphere.center;
    return dot(d, d) < sphere.radius * sphere.radius;
}

// the image: the type is usable again here, then hidden by a local in a block
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    sphere s = sphere(vec3(0.0), 1.0);
    { vec3 sphere = vec3(fragCoord, 0.0); fragColor = vec4(float(inside(s, sphere))); }
}
"""
    )
    result = _lint(tmp_path, text)
    assert not [f for f in result.findings if f.rule == "compile-error"]


# --- 3. normalize-known-length follows values --------------------------------------------------


def test_light_minus_sphere_center_is_not_a_sphere_normal(tmp_path: Path):
    text = (
        HEADER
        + """
// a sphere and a light
struct sSphere { vec4 center; float radius; };
struct sLight { vec4 center; float intensity; };

// light direction seen from the sphere's center, and the view direction
vec3 directions(in sSphere sphere, in sLight light, in vec4 rayOrigin)
{
    vec3 toLight = vec3(normalize(light.center - sphere.center));
    return toLight + vec3(normalize(rayOrigin - sphere.center));
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    sSphere s = sSphere(vec4(0.0, 0.0, -4.0, 1.0), 0.5);
    sLight l = sLight(vec4(1.0), 10.0);
    fragColor = vec4(directions(s, l, vec4(fragCoord, 0.0, 1.0)), 1.0);
}
"""
    )
    assert _lint(tmp_path, text, ["normalize-known-length"]).findings == []


def test_the_hit_point_of_a_literal_sphere_is_a_sphere_normal(tmp_path: Path):
    text = (
        HEADER
        + """
// the ray parameter where the ray meets the sphere
float hit_sphere(in vec3 center, in float radius, in vec4 rd, in vec4 ro)
{
    vec3 oc = ro.xyz - center;
    float a = dot(rd, rd);
    float half_b = dot(oc, rd.xyz);
    float c = dot(oc, oc) - radius * radius;
    float discriminant = half_b * half_b - a * c;
    return discriminant < 0.0 ? -1.0 : (-half_b - sqrt(discriminant)) / a;
}

// the image: the normal of the hit point
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec4 rd = vec4(fragCoord / iResolution.xy - 0.5, -1.0, 0.0);
    vec4 ro = vec4(0.0, 0.0, 0.0, 1.0);
    float t = hit_sphere(vec3(0, 0, -1), 0.5, rd, ro);
    vec4 hit = ro + t * rd;
    vec3 n = normalize(hit.xyz - vec3(0, 0, -1));
    fragColor = vec4(n * 0.5 + 0.5, 1.0);
}
"""
    )
    (f,) = _lint(tmp_path, text, ["normalize-known-length"]).findings
    assert f.loc.line == 23 and "0.5" in f.message and "/ 0.5" in f.help


def test_a_normalize_written_out_is_a_normalize(tmp_path: Path):
    # the same sphere, its normal normalized by hand (`v / sqrt(dot(v, v))`, `v / length(v)`)
    # of a hit point written `vec3(ro + t * rd)`: the radius is known; a light vector is not
    text = (
        HEADER
        + """
// the ray parameter where the ray meets the sphere
float hit_sphere(in vec3 center, in float radius, in vec4 rd, in vec4 ro)
{
    vec3 oc = vec3(ro) - center;
    float a = dot(rd, rd);
    float half_b = dot(oc, vec3(rd));
    float c = dot(oc, oc) - radius * radius;
    float discriminant = half_b * half_b - a * c;
    return discriminant < 0.0 ? -1.0 : (-half_b - sqrt(discriminant)) / a;
}

// the image: the normal of the hit point, and a light vector
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec4 rd = vec4(fragCoord / iResolution.xy - 0.5, -1.0, 0.0);
    vec4 ro = vec4(0.0, 0.0, 0.0, 1.0);
    float t = hit_sphere(vec3(0, 0, -1), 0.5, rd, ro);
    vec3 d = vec3(ro + t * rd) - vec3(0, 0, -1);
    vec3 n = d / sqrt(dot(d, d));
    vec3 l = (vec3(2.0) - d) / length(vec3(2.0) - d);
    fragColor = vec4(n * 0.5 + 0.5 + l, 1.0);
}
"""
    )
    (f,) = _lint(tmp_path, text, ["normalize-known-length"]).findings
    assert (
        f.loc.line == 23
        and "written out" in f.message
        and f.help == "divide by the radius: d / 0.5"
    )


PROCEDURAL = (
    HEADER
    + """
// the squared length
float lenSq(in vec2 v) { return dot(v, v); }

// the normal of the procedural sphere's point; its values come from the one caller
vec3 shade(in vec3 c, in vec2 d, in float lSq, in float rSq)
{
    vec3 pos = c + vec3(d, sqrt(rSq - lSq));
    return normalize(pos - c);
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 c = vec3(0.0, 0.0, -4.0);
    vec2 d = fragCoord - c.xy;
    float lSq = lenSq(d);
    fragColor = vec4(shade(c, d, lSq, 0.5 * 0.5), 1.0);
}
"""
)


def test_a_procedural_sphere_normal_followed_across_the_call(tmp_path: Path):
    (f,) = _lint(tmp_path, PROCEDURAL, ["normalize-known-length"]).findings
    assert (
        f.loc.line == 12
        and "built on the sphere" in f.message
        and f.help == "divide by the radius: (pos - c) / 0.5"
    )


def test_unsure_values_across_calls_are_silent(tmp_path: Path):
    # a second caller may pass anything; a squared length taken before d changes (f04's
    # `lSq = lengthSq(dp.xy)` before `dp.xy = ...`) is not the squared length of the new d
    second = PROCEDURAL.replace(
        "fragColor = vec4(shade(c, d, lSq, 0.5 * 0.5), 1.0);",
        "fragColor = vec4(shade(c, d, lSq, 0.25) + shade(c, d, 1.0, 0.25), 1.0);",
    )
    stale = PROCEDURAL.replace("float lSq = lenSq(d);", "float lSq = lenSq(d);\n    d *= 2.0;")
    for text in (second, stale):
        assert _lint(tmp_path, text, ["normalize-known-length"]).findings == []


# --- 4. repeats, lengths, inactive code, comments ---------------------------------------------


def test_one_finding_per_repeated_value_with_every_place(tmp_path: Path):
    text = (
        HEADER
        + """
// three lights on a circle
vec3 lights(in float time)
{
    return vec3(sin(time), cos(time), 0.0) + vec3(sin(time) * 2.0, 1.0, cos(time))
        + vec3(0.0, sin(time), 1.0);
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(lights(iTime), 1.0);
}
"""
    )
    result = _lint(tmp_path, text, ["repeated-expression"])
    assert [f.message for f in result.findings] == [
        "'sin(time)' is computed 3 times, with the same value, at lines 8 and 9",
        "'cos(time)' is computed twice, with the same value, at line 8",
    ]
    doc = json.loads(render(result, "json"))
    assert [n["line"] for n in doc["findings"][0]["notes"]] == [8, 9]


def test_an_array_length_is_not_a_geometric_length(tmp_path: Path):
    text = (
        HEADER
        + """
// sum of the lights' intensities
float total(in float intensities[4])
{
    float sum = 0.0;
    for (int i = 0; i < intensities.length(); ++i) { sum += intensities[i]; } // every light
    return sum;
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(total(float[4](1.0, 2.0, 3.0, 4.0)));
}
"""
    )
    assert (
        _lint(tmp_path, text, ["length-comparison", "sqrt-comparison", "loop-invariant"]).findings
        == []
    )


def test_inactive_ifdef_branches():
    lines = [
        "#define A",
        "#ifdef A",
        "x",
        "#else",
        "y",
        "#endif",
        "#ifndef A",
        "z",
        "#endif",
        "#if defined(B)",
        "w",
        "#elif 1",
        "v",
        "#endif",
        "#if FOO > 1",
        "u",
        "#endif",
    ]
    assert inactive_lines(lines) == {5, 8, 11}


def test_attribution_comments_explain_nothing(tmp_path: Path):
    text = (
        HEADER
        + """
// Code from class by Daniel Buckstein
float lenSq(in vec2 x)
{
    return dot(x, x);
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(lenSq(fragCoord));
}
"""
    )
    # the rubric asks for the why: a credit says where code came from, so a TA deducts there
    (f,) = _lint(tmp_path, text, ["missing-comment"]).findings
    assert (f.severity, f.penalty, f.certainty, f.loc.line) == ("warning", 1, "certain", 6)


def test_the_same_value_written_differently(tmp_path: Path):
    text = (
        HEADER
        + """
// squared length
float lenSq(in vec2 x)
{
    return dot(x, x);
}

// inside the circle, then the sphere's height from the same squared distance written out
float height(in vec3 dp, in float rSq, in vec4 rd)
{
    float lSq = lenSq(dp.xy);
    float a = length(rd) * length(rd);
    return lSq <= rSq ? sqrt(rSq - (dp.x * dp.x + dp.y * dp.y)) * a : 0.0;
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(height(vec3(fragCoord, 0.0), 1.0, vec4(1.0)));
}
"""
    )
    found = [
        (f.loc.line, f.message) for f in _lint(tmp_path, text, ["repeated-expression"]).findings
    ]
    assert found == [
        (15, "'length(rd)' is computed twice, with the same value, at line 15"),
        (16, "'lenSq(dp.xy)' is computed twice, with the same value, at lines 14 and 16"),
    ]


def test_a_broken_directive_drops_only_its_line(tmp_path: Path):
    text = (
        HEADER
        + "#define SCALE(x (x * 2.0)\n// a uniform in a helper\nfloat t() { return iTime; }\n"
        "// the image\nvoid mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor = "
        "vec4(t()); }\n"
    )
    found = [(f.rule, f.severity, f.loc.line) for f in _lint(tmp_path, text).findings]
    assert found[0] == ("compile-error", "error", 4)
    assert ("uniform-outside-mainimage", "warning", 6) in found


def test_a_value_written_again_inside_a_product_chain(tmp_path: Path):
    # `d / k * d / k` is ((d / k) * d) / k: `d / k` twice, though only one is a subtree;
    # `c * d / k` writes it once more; `(d * d) / (k * c)` does not write `d / k` (as in the
    # course's attenuation formula, `(d * d) / (k * k)`): not a place of it
    text = (
        HEADER
        + """
// attenuation, written three ways
float atten(in float d, in float k, in float c)
{
    float a = 1.0 / (1.0 + d / k * d / k * c);
    float b = 1.0 / (2.0 + (d * d) / (k * c));
    return a + b + c * d / k;
}

// integer quotients round: `i / j * i / j` is not `(i / j) * (i / j)`
int steps(in int i, in int j)
{
    return i / j * i / j;
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(atten(fragCoord.x, 2.0, 3.0) + float(steps(int(fragCoord.x), 3)));
}
"""
    )
    found = [
        (f.loc.line, f.message) for f in _lint(tmp_path, text, ["repeated-expression"]).findings
    ]
    assert found == [(8, "'d / k' is computed 3 times, with the same value, at lines 8 and 10")]


def test_a_mainimage_macro_in_common_reads_the_pass_uniforms(tmp_path: Path):
    # the macro expands in the Image pass's wrapper, where iTime is declared; Common compiled
    # alone never expands it. A Common *function* reading iTime is still an error.
    (tmp_path / "Common.glsl").write_text(
        HEADER + "// the whole image, golfed\n#define mainImage(O, U) O = vec4(sin(iTime), "
        "U / iResolution.xy, 1.0)\n"
    )
    (tmp_path / "Image.glsl").write_text(HEADER + "// the image is the Common tab's macro\n")
    result = lint_paths(
        [tmp_path / "Common.glsl", tmp_path / "Image.glsl"], {"select": ["compile-error"]}
    )
    assert result.findings == []
    (tmp_path / "Common.glsl").write_text(
        HEADER + "// the time\nfloat t() { return iTime; }\n"
        "#define mainImage(O, U) O = vec4(t(), U / iResolution.xy, 1.0)\n"
    )
    found = [
        (f.rule, f.loc.line, "'iTime' is not available in the Common tab" in f.message)
        for f in lint_paths([tmp_path / "Common.glsl"], {"select": ["compile-error"]}).findings
    ]
    assert (("compile-error", 5, True)) in found


def test_a_uniform_the_shader_declares_is_a_uniform_too(tmp_path: Path):
    text = (
        HEADER
        + """
// the diffuse map (a uniform of the shader's own)
uniform sampler2D diffuseMap;

// the texture's colour (reads the uniform: a deduction, as for iChannel0)
vec4 diffuse(in vec2 uv)
{
    return texture(diffuseMap, uv) + texture(iChannel0, uv);
}

// the image
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = diffuse(fragCoord) + texture(diffuseMap, fragCoord);
}
"""
    )
    found = [
        (f.loc.line, f.message)
        for f in _lint(tmp_path, text, ["uniform-outside-mainimage"]).findings
    ]
    assert found == [
        (11, "the uniform 'diffuseMap' is read in 'diffuse', not in mainImage"),
        (11, "the uniform 'iChannel0' is read in 'diffuse', not in mainImage"),
    ]
