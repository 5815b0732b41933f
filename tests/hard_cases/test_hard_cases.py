"""The hard cases (see README.md here): verify (NumPy vs llvmpipe) on each, and pins.

Two kinds of test:
- `test_verify_passes`: cases where GLSL and llvmpipe give a definite run-time answer; the NumPy
  backend must copy it (NaN/Inf included) and verify must pass at several times. (No known
  difference is left: see README.md here.)
- `test_numpy_pinned_*` / `test_llvmpipe_pinned_*`: where llvmpipe's answer depends on constant
  folding, reassociation, or is garbage, the NumPy backend's documented choice is pinned, and so
  is what llvmpipe returns (when it is deterministic), so the README table stays true.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.verify import compile_backend, verify

HERE = Path(__file__).resolve().parent
SIZE = (160, 90)
W, H = SIZE
TIMES = [0.0, 1.7, 5.3]

VERIFIED = [
    "tangent_sphere",
    "silhouette_exact",
    "light_at_surface",
    "pow_edge",
    "far_camera",
    "intensities",
    "int_overflow",
    "mod_negative",
    "atan_zero",
    "int_mod_negative",
    "div_zero",
    "pow_literal_exponent",
    "atan_nan",
]
PINNED = ["constant_folding", "reassociation", "smoothstep_equal"]


def test_every_case_is_listed():
    listed = set(VERIFIED) | set(PINNED)
    on_disk = {p.stem for p in HERE.glob("*.glsl")}
    assert listed == on_disk
    readme = (HERE / "README.md").read_text()
    missing = [name for name in on_disk if f"{name}.glsl" not in readme]
    assert not missing, f"no README.md row for {missing}"


def _render(name: str, backend: str, time: float = 0.0) -> np.ndarray:
    return compile_backend(load_shader(HERE / f"{name}.glsl"), backend).render(size=SIZE, time=time)


def _at(img: np.ndarray, x: int, y: int) -> np.ndarray:
    """RGB at fragCoord (x + 0.5, y + 0.5): y counts from the bottom as in the shader."""
    return img[H - 1 - y, x, :3]


@pytest.mark.parametrize("name", VERIFIED)
def test_verify_passes(gl, name):
    for time, comparison in zip(TIMES, verify(HERE / f"{name}.glsl", size=SIZE, times=TIMES)):
        assert comparison.match, f"{name} at iTime {time}: {comparison.summary()}"


# --- what llvmpipe returns (the README's middle column), at the pixels the shaders aim at -----
# The centre pixel is (80, 45): fragCoord (80.5, 45.5) = floor(iResolution.xy / 2) + 0.5.


def test_llvmpipe_pinned_run_time_answers(gl):
    img = _render("pow_edge", "gl")
    assert _at(img, 80, 45)[0] == 0.0  # pow(0, 0) = 0 at run time
    assert _at(img, 80, 30)[0] == 0.0  # pow(0, y < 0) = 0
    assert np.isnan(_at(img, 40, 45)[0])  # pow(x < 0, 0) = NaN
    img = _render("light_at_surface", "gl")
    centre = _at(img, 80, 45)
    assert centre[0] == 1.0  # max(dot(N, NaN), 0) = 0, plus light 2 overhead
    assert np.isnan(centre[1]) and centre[2] == math.inf  # length(normalize(0)) = NaN, 100/0 = +Inf
    img = _render("atan_zero", "gl")
    assert _at(img, 80, 45)[0] * 6.2831853 - 3.14159265 == pytest.approx(3 * math.pi / 4, abs=1e-5)
    img = _render("div_zero", "gl")
    assert (
        np.isnan(_at(img, 80, 45)[0])
        and _at(img, 80, 60)[0] == math.inf
        and _at(img, 80, 30)[0] == -math.inf
    )
    assert _at(img, 40, 45)[1] == pytest.approx(0.25)  # int / 0 = 0 and int % 0 = -1
    img = _render("int_mod_negative", "gl")
    assert _at(img, 40, 45)[0] == pytest.approx(
        6 / 15
    )  # -40 % 7 = unsigned remainder 6 (C: -5, Python: 2)
    img = _render("silhouette_exact", "gl")
    assert int((img[..., 1] == 1.0).sum()) == 20  # h == 0 exactly at the 20 lattice points
    img = _render("atan_nan", "gl")
    assert _at(img, 80, 45)[0] == pytest.approx(0.5)  # atan(NaN) = 0


def test_llvmpipe_pinned_folding_and_reassociation(gl):
    img = _render("constant_folding", "gl")
    bands = [_at(img, x, 45)[0] for x in (20, 60, 100, 140)]
    assert bands == [1.0, 1.0, 0.5, 0.25]  # pow(-2,2)=4, pow(0,0)=1, -7%2=-1, atan(0,0)=0 folded
    img = _render("reassociation", "gl")
    assert np.all(img[..., 0] == math.inf)  # k * 1e30 * 1e9: 1e30 * 1e9 folded to +Inf
    assert np.all(np.isfinite(img[..., 1]))  # (k * 1e30) * g * 1e-30: 1e30 * 1e-30 folded to 1
    img = _render("pow_literal_exponent", "gl")
    x = -80.5 / W
    assert _at(img, 80, 45)[0] == pytest.approx(x * x) and _at(img, 80, 45)[1] == pytest.approx(-x)
    assert _at(img, 80, 80)[2] == pytest.approx(4 * x**4) and np.isnan(_at(img, 80, 10)[2])


# --- the NumPy backend's documented choices (the README's last column) ------------------------


def test_numpy_pinned_choices():
    img = _render("constant_folding", "numpy")
    band = [_at(img, x, 45)[0] for x in (20, 60, 100, 140)]
    # pow and atan are not folded, but pow's literal exponent 2.0 is rewritten to x*x as Mesa
    # does (pow(-2, 2) = 4, Mesa's folded answer too); pow(0, 0.0) and atan(0, 0) keep the
    # run-time answers (0, 3*pi/4); the transpiler folds int % of constants with C's
    # remainder (runtime.rem_const), as Mesa does: -7 % 2 = -1.
    assert band[0] == 1.0 and band[1] == 0.0 and band[2] == 0.5
    assert band[3] == pytest.approx(2.3561912 + 0.25, abs=1e-6)  # llvmpipe's run-time 3*pi/4
    img = _render("reassociation", "numpy")
    assert np.all(
        img[..., 0] == math.inf
    )  # k * 1e30 * 1e9: 1e30 * 1e9 merged first, as Mesa (nir_fold)
    assert (
        _at(img, 150, 45)[1] == math.inf
    )  # right: (k * 1e30) * g overflows before * 1e-30 (not copied)
    img = _render("smoothstep_equal", "numpy")
    equal = img[H // 2, :, 0]  # the formula: 0 left of and on the edge, 1 right of it
    assert np.all(equal[:81] == 0.0) and np.all(equal[81:] == 1.0)


def test_smoothstep_equal_edges_is_not_pinned_on_llvmpipe(gl):
    """llvmpipe returns run-to-run garbage there; only check that it is not the formula's answer
    everywhere, so the README claim is re-checked (if Mesa fixes it, this fails and says so)."""
    img = _render("smoothstep_equal", "gl")
    equal = img[H // 2, :, 0]
    formula = np.r_[np.zeros(81), np.ones(W - 81)]
    assert not np.array_equal(equal, formula), "llvmpipe now follows the formula: update README.md"
