"""A float literal's decimal is rounded to float32 once, as a GPU's compiler reads it: a decimal
just off a float32 halfway point must not be rounded to float64 first (landing on the halfway
point) and then to even. float64 renders keep the float64 nearest the decimal."""

from __future__ import annotations

import random
import struct
from fractions import Fraction

import numpy as np
import pytest

import glslcheck
from glslcheck.base.precision import float32_literal

ABOVE_HALF = (
    "1.00000005960464477539062500000000001"  # 1 + 2**-24 (halfway to the next float32) + 1e-35
)


def _nearest_float32(exact: Fraction) -> float:
    """The float32 nearest `exact`, ties to even, by comparing it with its two float32
    neighbours."""
    lo = np.float32(float(exact))
    while Fraction(float(lo)) > exact:
        lo = np.nextafter(lo, np.float32(-np.inf))
    while Fraction(float(np.nextafter(lo, np.float32(np.inf)))) <= exact:
        lo = np.nextafter(lo, np.float32(np.inf))
    hi = np.nextafter(lo, np.float32(np.inf))
    below, above = exact - Fraction(float(lo)), Fraction(float(hi)) - exact
    if below != above:
        return float(lo if below < above else hi)
    return float(lo if int(lo.view(np.uint32)) % 2 == 0 else hi)


def _decimals(count: int = 300) -> list[str]:
    """Decimals on, just above and just below float32 halfway points, and plain ones."""
    rng = random.Random(41)
    out = []
    for _ in range(count):
        x = np.float32(rng.uniform(-1e6, 1e6) * 2.0 ** rng.randint(-60, 60))
        nxt = np.nextafter(x, np.float32(np.inf))
        half = (Fraction(float(x)) + Fraction(float(nxt))) / 2
        digits = (
            len(str(half.denominator)) + 40
        )  # enough decimals for the halfway point, and 40 more
        for offset in (0, Fraction(1, 10**digits), -Fraction(1, 10**digits)):
            value = half + offset
            sign = "-" if value < 0 else ""
            whole, frac = divmod(abs(value.numerator) * 10**digits // value.denominator, 10**digits)
            out.append(f"{sign}{whole}.{frac:0{digits}d}")
        out.append(repr(rng.uniform(-1e3, 1e3)))
    return out


def test_a_literal_is_the_float32_nearest_its_decimal():
    wrong_before = 0
    for text in _decimals():
        exact = Fraction(text)
        assert float32_literal(text) == _nearest_float32(exact), text
        wrong_before += float(np.float32(float(text))) != _nearest_float32(exact)
    assert wrong_before > 0  # the set holds decimals that rounding through float64 gets wrong


def test_the_halfway_point_itself_rounds_to_even():
    half = Fraction(1) + Fraction(1, 2**24)
    assert Fraction(ABOVE_HALF) > half
    assert float32_literal(ABOVE_HALF) == float(np.nextafter(np.float32(1), np.float32(2)))
    assert float32_literal("1.000000059604644775390625") == 1.0  # exactly halfway: to even
    assert float32_literal("1e39") == float("inf") and float32_literal("1e-50") == 0.0


SHADER = f"""void mainImage(out vec4 fragColor, in vec2 fragCoord)
{{
    const float folded = ({ABOVE_HALF} - 1.0) * 8388608.0;
    float a = {ABOVE_HALF};
    fragColor = vec4((a - 1.0) * 8388608.0, folded, a > 1.0 ? 1.0 : 0.0, 1.0);
}}
"""


@pytest.fixture
def shader(tmp_path):
    path = tmp_path / "Image.glsl"
    path.write_text(SHADER)
    return str(path)


def test_cpu_engines_read_the_literal_as_gl_does(shader, gl):
    expected = (float32_literal(ABOVE_HALF) - 1.0) * 2**23
    theirs = glslcheck.compile(shader, backend="gl").render(size=(2, 2))
    assert theirs[0, 0, 0] == expected and theirs[0, 0, 1] == expected
    ours = glslcheck.compile(shader, backend="numpy").render(size=(2, 2))
    assert np.array_equal(ours, theirs)


def test_the_compiled_engine_reads_the_literal_as_gl_does(shader, gl, numba):
    theirs = glslcheck.compile(shader, backend="gl").render(size=(2, 2))
    ours = glslcheck.compile(shader, backend="compiled").render(size=(2, 2))
    assert np.array_equal(ours, theirs)


def test_float64_keeps_the_float64_nearest_the_decimal(shader):
    ours = glslcheck.compile(shader, backend="numpy").render(size=(2, 2), precision="float64")
    assert ours[0, 0, 0] == np.float32((float(ABOVE_HALF) - 1.0) * 2**23)
    assert (
        struct.unpack("<f", struct.pack("<f", float(ABOVE_HALF)))[0] == 1.0
    )  # float64 is the halfway point


def test_literals_at_the_top_of_float32s_range_read_as_gl_reads_them(tmp_path, gl):
    # just below the halfway point between float32's largest and 2**128 (its float64 is that point)
    below_overflow = "3.402823567797336616375393954581425684479e38"
    path = tmp_path / "Image.glsl"
    path.write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n"
        f"    float a = 1e39;\n    float b = {below_overflow};\n"
        "    fragColor = vec4(a > 1.0 ? 1.0 : 0.0, b / 3.4e38, isinf(b) ? 1.0 : 0.0, 1.0);\n}\n"
    )
    theirs = glslcheck.compile(str(path), backend="gl").render(size=(2, 2))
    assert theirs[0, 0, 2] == 0.0 and float32_literal(below_overflow) == float(
        np.finfo(np.float32).max
    )
    assert np.array_equal(glslcheck.compile(str(path), backend="numpy").render(size=(2, 2)), theirs)
