"""The lab itself (lab_shaders/): the standing proof that glslcheck works on the real thing.

Every part is valid for the reference compiler (its Common tab also alone, as Shadertoy
compiles it), checks and lints clean under the course's rules, and renders finite (no NaN or
Inf) on both backends over a sweep of 50 times. Verify against OpenGL at several times is in
tests/verify; golden images in tests/golden.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from glslcheck.shadertoy.sources import load_shader

ROOT = Path(__file__).resolve().parents[2]
PARTS = sorted(p for p in (ROOT / "lab_shaders").iterdir() if p.is_dir())
# 50 times over the first 10 seconds, irrational steps so no two parts see only round times.
TIMES = [i * 0.2017 for i in range(50)]
# Small frames: a NaN or Inf comes from a formula's domain (pow of a negative, 0/0), which a
# 48x27 frame samples at the same places as a large one (spheres, edges, background all hit).
SIZE = (48, 27)


def test_every_part_of_the_assignment_is_there():
    names = {p.name for p in PARTS}
    for needed in [
        "01_spheres_raytraced",
        "01_spheres_procedural",
        "02_point_light",
        "03_lambert_coefficient",
        "03_lambert_attenuation",
        "03_lambert_color",
        "04_phong_coefficient",
        "04_phong_exponents",
        "04_phong_color",
        "04_phong_summation",
        "05_blinn_phong",
        "06_multiple_lights",
        "07_final",
        "bonus_animated_lights",
        "bonus_spot_lights",
        "bonus_cel_shading",
        "bonus_gooch_shading",
    ]:
        assert needed in names


@pytest.mark.parametrize("part", PARTS, ids=lambda p: p.name)
def test_reference_compiler_accepts_part_and_its_common_alone(part, glslang):
    from glslcheck.semantics.glslang import validate
    from glslcheck.shadertoy.wrapper import build_common_only, build_program

    shader = load_shader(part)
    assert validate(build_program(shader).text).ok
    if shader.common is not None:
        assert validate(build_common_only(shader).text).ok


def test_lab_checks_and_lints_clean():
    from glslcheck.cli.main import main

    assert main(["check", str(ROOT / "lab_shaders")]) == 0
    from glslcheck.lint import lint_paths

    result = lint_paths([str(ROOT / "lab_shaders")])
    assert result.files == 2 * len(PARTS)
    assert [f"{f.loc}: {f.rule} {f.message}" for f in result.findings] == []


@pytest.mark.parametrize("part", PARTS, ids=lambda p: p.name)
def test_part_renders_finite_over_50_times_on_both_backends(part, gl, shader_check):
    # the project's own plugin (glslcheck/testing.py): a failure names the pixels and the
    # probe command, and keeps a picture of them
    for backend in ("numpy", "gl"):
        shader_check.assert_no_nan(part, times=TIMES, size=SIZE, backend=backend)


@pytest.mark.parametrize("part", [p for p in PARTS if p.name.startswith("bonus_animated")])
def test_the_animated_bonus_animates_on_both_backends(part, gl, shader_check):
    for backend in ("numpy", "gl"):
        shader_check.assert_animates(part, times=TIMES[:3], size=SIZE, backend=backend)
