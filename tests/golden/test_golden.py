"""Golden images: every lab part rendered by the GL backend at 320x180, iTime 1.0, as 8-bit PNG.

The PNGs were looked at by eye before they were committed. Both backends are compared to them,
so a change in the driver, the Shadertoy wrapper or the NumPy backend shows up as a failing
image, not only as a verify mismatch. Regenerate with `pytest tests/golden --update-snapshots`,
then look at them again.

Tolerance. The goldens are 8-bit: golden = Q(gl) with Q(x) = round(255 * clamp(x, 0, 1)) / 255,
and a render r is compared after the same quantisation. Q moves a value by at most 0.5/255, so
|Q(r) - Q(gl)| <= |r - gl| + 1/255: a render within verify's float tolerance (2/255, see
glslcheck/verification/compare.py step 4) of the render the golden came from is within 3/255 of the
golden, and 3/255 is what we allow per channel. The rest of the model (edge pixels, pixel budgets,
NaN/Inf: a PNG holds none, Q maps NaN to 0 as the display does) is verify's own, unchanged.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from glslcheck.base.images import load_image, quantise, save_image
from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.compare import compare
from glslcheck.verification.verify import compile_backend

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = Path(__file__).resolve().parent
LAB_PARTS = sorted(p.name for p in (ROOT / "lab_shaders").iterdir() if (p / "Image.glsl").is_file())
SIZE = (320, 180)
TIME = 1.0
GOLDEN_TOL = 3.0 / 255.0  # verify's 2/255 plus two half-steps of 8-bit rounding (docstring)


def test_every_lab_part_has_a_golden():
    assert LAB_PARTS, "no lab parts found"
    missing = [p for p in LAB_PARTS if not (GOLDEN / f"{p}.png").is_file()]
    assert not missing, f"no golden image for {missing}; run pytest tests/golden --update-snapshots"
    stale = sorted(p.stem for p in GOLDEN.glob("*.png") if p.stem not in LAB_PARTS)
    assert not stale, f"golden images of lab parts that no longer exist: {stale}"


@pytest.mark.parametrize("backend", ["gl", "numpy"])
@pytest.mark.parametrize("part", LAB_PARTS)
def test_render_matches_golden(gl, update_snapshots, part, backend):
    shader = load_shader(ROOT / "lab_shaders" / part)
    path = GOLDEN / f"{part}.png"
    if update_snapshots and backend == "gl":
        save_image(
            compile_backend(shader, "gl").render(size=SIZE, time=TIME), path
        )  # 8-bit, as quantise
    img = compile_backend(shader, backend).render(size=SIZE, time=TIME)
    assert img.shape == (SIZE[1], SIZE[0], 4)
    golden = load_image(path)  # float RGBA in [0, 1]: the 8-bit values / 255
    comparison = compare(quantise(img), golden, abs_tol=GOLDEN_TOL)  # compare scales uint8 by 1/255
    assert comparison.match, f"{part} ({backend}) vs {path.name}: {comparison.summary()}"
