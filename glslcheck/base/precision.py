"""The float precisions the NumPy backend renders in: the one list that the runtime, the API, the
CLI (`--precision`), verify and bench all use.

- "float16": GLSL mediump, emulated: values are stored as float16 (backends/numpy_engine/runtime.py);
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
