"""The float precisions the NumPy backend renders in: the one list that the runtime, the API, the
CLI (`--precision`), verify and bench all use.

- "float16": GLSL mediump, emulated: values are stored as float16
  (backends/numpy_engine/runtime.py);
- "float32": GLSL highp, what the GPU driver (llvmpipe) computes in; the default;
- "float64": a reference, the shader's arithmetic without float32's rounding.

The GL and WebGL backends render in float32 only (the driver's highp). No NumPy here: the CLI
builds its parsers from this list at start-up.
"""

from __future__ import annotations

PRECISIONS = ("float16", "float32", "float64")  # from the least precise (bench's order)


def check_precision(precision: str) -> str:
    """`precision`, or ValueError naming the ones there are."""
    if precision not in PRECISIONS:
        raise ValueError(f"precision must be one of {', '.join(PRECISIONS)}, not {precision!r}")
    return precision


def float32_literal(text: str) -> float:
    """The float32 a GLSL float literal's decimal `text` (`1.5`, `.5e-3`, `2.f`) denotes: the
    float32 nearest the exact decimal, ties to even (what a GPU's compiler reads), as a Python
    float; overflow gives +-inf. Rounding through float64 first is wrong only when the nearest
    float64 is exactly halfway between two float32 and the decimal is not: then the side of the
    halfway point the decimal lies on decides, computed exactly."""
    import math
    import struct

    digits = text.rstrip("fF")
    v = float(digits)
    if math.isinf(v) or math.isnan(v):
        return v
    try:
        bits = struct.unpack("<I", struct.pack("<f", v))[0]
    except OverflowError:  # at or past the halfway point between float32's largest and 2**128
        bits = 0x7F800000 | (0x80000000 if v < 0 else 0)
    r = struct.unpack("<f", struct.pack("<I", bits))[0]
    if r == v:
        return r
    # the float32 next to r on v's side: v lies between r and it
    other = struct.unpack("<f", struct.pack("<I", bits + 1 if abs(v) > abs(r) else bits - 1))[0]
    from fractions import Fraction  # only for a literal whose float64 is not a float32

    exact_r = Fraction(r) if not math.isinf(r) else Fraction(int(math.copysign(2**128, r)))
    half = (exact_r + Fraction(other)) / 2
    if Fraction(v) != half:
        return r
    exact = Fraction(digits)
    if exact == half:
        return r  # a true tie: rounded to even already
    return r if (exact < half) == (exact_r < half) else other
