"""`verify --against webgl` sets apart the pixels that depend on the shader's undefined reads
(tests/verify/undefined: each read marked `// undefined: KIND`), as verify against GL does."""

from __future__ import annotations

from pathlib import Path

import pytest

from glslcheck.base.diagnostics import GlslError
from glslcheck.verification.drivers import verify_against_webgl

CASES = Path(__file__).resolve().parents[1] / "verify" / "undefined"
SHADERS = sorted(p.name for p in CASES.glob("*.glsl"))


def _marked_lines(path: Path) -> set[int]:
    lines = path.read_text().splitlines()
    return {n for n, line in enumerate(lines, 1) if "// undefined:" in line}


@pytest.mark.parametrize("name", SHADERS)
def test_webgl_differs_only_where_undefined(name, webgl, gl):
    """With WebGL's zeros the ray tracer's `while (true)` never ends (its seed is always 0):
    the NumPy renderer stops it, and the error names the undefined read as the likely cause."""
    path = CASES / name
    try:
        (result,) = verify_against_webgl(path, size=(32, 18))
    except GlslError as e:
        (error,) = e.diagnostics
        assert error.rule == "numpy-runaway-loop"
        assert {n.loc.line for n in error.notes} == _marked_lines(path)
        return
    c = result.comparison
    assert c.verdict in ("match", "undefined"), c.summary()
    assert c.mismatched_pixels == 0 and c.nan_mismatched_pixels == 0
    if c.undefined_pixels:
        assert {u["line"] for u in c.undefined_lines} <= _marked_lines(path)
