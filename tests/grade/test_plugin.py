"""The pytest plugin glslcheck.testing as a course autograder uses it: test files run by
pytester, the passing ones and the ones that must fail, whose messages carry the numbers and a
diff image that exists."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest
from lab_class import CLAMP, FINAL, ROOT

from glslcheck.testing import RenderMismatch, ShaderCheck
from glslcheck.verification.compare import compare

GOLDEN = ROOT / "tests" / "golden" / "07_final.png"
ANIMATED = ROOT / "lab_shaders" / "bonus_animated_lights"
SIZE = (96, 54)


def _variant(tmp_path: Path, name: str, tab: str, old: str, new: str) -> Path:
    folder = tmp_path / name
    shutil.copytree(FINAL, folder)
    text = (folder / tab).read_text()
    assert old in text
    (folder / tab).write_text(text.replace(old, new))
    return folder


@pytest.fixture
def bug(tmp_path) -> Path:
    return _variant(tmp_path, "bug", "Common.glsl", CLAMP, "dot(normal, lightDir) * attenuated")


@pytest.fixture
def nan_shader(tmp_path) -> Path:
    folder = tmp_path / "nan"
    folder.mkdir()
    (folder / "Image.glsl").write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        "    vec2 uv = fragCoord / iResolution.xy;\n"
        "    fragColor = vec4(sqrt(uv.x - 0.5), uv.y, 0.25, 1.0);\n}\n"
    )
    return folder


def _run(pytester, body: str):
    pytester.makepyfile(test_student=body)
    return pytester.runpytest("-p", "glslcheck.testing", "-p", "no:cacheprovider", "-q")


def test_a_correct_part_passes_every_assertion(pytester):
    result = _run(
        pytester,
        f"""
def test_part_renders_like_the_reference(shader_check):
    shader_check.assert_renders_like({str(FINAL)!r}, {str(FINAL)!r}, times=[0, 1.7], size={SIZE})

def test_part_is_finite(shader_check):
    shader_check.assert_no_nan({str(FINAL)!r}, times=[0, 1.7, 5.3], size={SIZE})

def test_animated_lights_animate(shader_check):
    shader_check.assert_animates({str(ANIMATED)!r}, times=[0, 1.7], size={SIZE})

def test_part_looks_like_its_golden_image(shader_check):
    shader_check.assert_matches_png({str(FINAL)!r}, {str(GOLDEN)!r})
""",
    )
    result.assert_outcomes(passed=4)


def _diff_path(text: str, label: str = "diff image") -> Path:
    path = Path(re.search(label + r": (\S+\.png)", text).group(1))
    assert path.is_file() and path.stat().st_size > 0
    return path


def test_a_lighting_bug_fails_with_the_numbers_and_a_diff_image(pytester, bug):
    result = _run(
        pytester,
        f"""
def test_part3(shader_check):
    shader_check.assert_renders_like({str(bug)!r}, {str(FINAL)!r}, times=[0, 1.7], size={SIZE})
""",
    )
    result.assert_outcomes(failed=1)
    text = result.stdout.str()
    line = next(ln for ln in text.split("\n") if "does not render like" in ln)
    assert f"{bug} does not render like {FINAL} at iTime 0 (tolerance 'same'" in line
    # the figures are compare's own on the same renders
    check = ShaderCheck(SIZE)
    c = compare(check.render(bug, 0.0), check.render(FINAL, 0.0))
    assert f"PSNR {c.psnr_db:.1f} dB" in line and f"max abs error {c.max_abs_error:.4g}" in line
    assert f"({c.mismatched_pixels} mismatched, budget {int(c.mismatch_budget)};" in line
    assert "worst at pixel" in line
    assert _diff_path(line).parent.name == "glslcheck"  # under the failing test's tmp_path


def test_tolerances_same_close_and_a_psnr(tmp_path):
    # a Blinn-Phong exponent halved: the same scene, a wider highlight (docs/grading.md: 32 dB)
    wider = _variant(tmp_path, "wider", "Image.glsl", "4.0 * 32.0", "4.0 * 16.0")
    check = ShaderCheck(SIZE, diff_dir=tmp_path / "diffs")
    (c,) = check.assert_renders_like(wider, FINAL, tolerance="close")
    assert not c.match and c.psnr_db >= 30.0
    check.assert_renders_like(wider, FINAL, tolerance=c.psnr_db)  # a PSNR in dB passes at it
    with pytest.raises(RenderMismatch, match=r"tolerance 'same': verify's match\): PSNR"):
        check.assert_renders_like(wider, FINAL)
    with pytest.raises(RenderMismatch, match=r"PSNR >= "):
        check.assert_renders_like(wider, FINAL, tolerance=c.psnr_db + 0.5)
    with pytest.raises(ValueError, match="tolerance must be"):
        check.assert_renders_like(wider, FINAL, tolerance="roughly")


def test_nan_pixels_fail_with_their_count_place_and_the_probe_command(pytester, nan_shader):
    result = _run(
        pytester,
        f"""
def test_part(shader_check):
    shader_check.assert_no_nan({str(nan_shader)!r}, size=(64, 36))
""",
    )
    result.assert_outcomes(failed=1)
    text = result.stdout.str()
    # sqrt of a negative left of the middle column: x < 32 of 64, every row
    assert "has 1152 NaN/Inf pixels of 2304 at iTime 0 (64x36), in x 0..31, y 0..35" in text
    assert f"glslcheck probe {nan_shader} --nan --time 0 --size 64x36" in text
    _diff_path(text, "the pixels in magenta")


def test_a_still_picture_fails_the_animation_assertion(pytester):
    result = _run(
        pytester,
        f"""
def test_part(shader_check):
    shader_check.assert_animates({str(FINAL)!r}, times=[0, 1.7, 5.3], size={SIZE})
""",
    )
    result.assert_outcomes(failed=1)
    text = result.stdout.str()
    assert (
        f"{FINAL} does not animate: the frames at iTime 0, 1.7, 5.3 differ from the first" in text
    )
    _diff_path(text)


def test_a_png_of_another_part_fails_and_keeps_the_render(pytester):
    other = ROOT / "tests" / "golden" / "06_multiple_lights.png"
    result = _run(
        pytester,
        f"""
def test_part(shader_check):
    shader_check.assert_matches_png({str(FINAL)!r}, {str(other)!r})
""",
    )
    result.assert_outcomes(failed=1)
    text = result.stdout.str()
    assert f"does not look like {other}" in text
    _diff_path(text)
    _diff_path(text, "the render")


def test_the_size_option_reaches_the_fixture(pytester):
    pytester.makepyfile(
        test_size="def test_size(shader_check):\n    assert shader_check.size == (40, 30)\n"
    )
    result = pytester.runpytest("-p", "glslcheck.testing", "--glslcheck-size", "40x30")
    result.assert_outcomes(passed=1)
    bad = pytester.runpytest("-p", "glslcheck.testing", "--glslcheck-size", "forty")
    assert bad.ret != 0


def _autograder(pytester, common_text: str) -> None:
    """docs/autograder.md's layout in the pytester folder, its test file as the page has it."""
    doc = (ROOT / "docs" / "autograder.md").read_text()
    code = re.search(r"```python\n(.*?)```", doc, re.S).group(1)
    pytester.makepyfile(test_part3=code)
    part = ROOT / "lab_shaders" / "03_lambert_color"
    shutil.copytree(part, pytester.path / "reference" / "part3")
    team = pytester.path / "submission" / "lab4"
    team.mkdir(parents=True)
    (team / "Image.txt").write_text((part / "Image.glsl").read_text())
    (team / "Common.txt").write_text(common_text)


def test_the_documented_autograder_passes_the_reference_itself(pytester):
    _autograder(pytester, (ROOT / "lab_shaders" / "03_lambert_color" / "Common.glsl").read_text())
    pytester.runpytest("-p", "glslcheck.testing", "-p", "no:cacheprovider").assert_outcomes(
        passed=5
    )


def test_the_documented_autograder_fails_the_unnormalised_light_vector(pytester):
    common = (ROOT / "lab_shaders" / "03_lambert_color" / "Common.glsl").read_text()
    assert "    return toLight * invDist;" in common
    _autograder(pytester, common.replace("    return toLight * invDist;", "    return toLight;"))
    result = pytester.runpytest("-p", "glslcheck.testing", "-p", "no:cacheprovider")
    result.assert_outcomes(passed=4, failed=1)
    text = result.stdout.str()
    assert "FAILED test_part3.py::test_part3_renders_like_the_reference" in text
    assert "tolerance 'close': PSNR >= 30 dB): PSNR " in text
    _diff_path(text)
