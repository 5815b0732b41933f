"""How close a submission's picture is to the reference's, on a scale a TA can act on, and what
a single render says by itself (NaN or Inf pixels, one flat colour, no animation).

The scale, per frame, worst frame for the submission (docs/grading.md argues each threshold):

- **same picture**: `verify`'s own verdict (glslcheck/verification/compare.py) says the two
  renders match: every difference is one the 8-bit display cannot show (2/255 per channel) or a
  sub-pixel shift of an edge, within verify's budgets. Two renders of one program on two
  drivers differ this much; nothing a viewer sees is different.
- **close**: PSNR of the displayed images at least CLOSE_PSNR_DB (30 dB: a root-mean-square
  error of 8/255 over the image). The same scene with a parameter changed (a highlight
  exponent, the ambient level, a light moved or dimmed, Phong for Blinn-Phong) lands at 32-47
  dB on the lab's final scene; the TA looks at the thumbnails and decides.
- **different**: below that. Lighting bugs (no clamp of N.L, no attenuation), a missing term (no
  specular: 28.3 dB) and any other part of the lab (20.5 dB at most) land here.

A frame with NaN or Inf pixels where the reference has none is "different" whatever its PSNR.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ...base.images import quantise
from ..compare import DEFAULT_ABS_TOL, Comparison

SAME, CLOSE, DIFFERENT = "same picture", "close", "different"
VERDICTS = (SAME, CLOSE, DIFFERENT)  # best first
CLOSE_PSNR_DB = 30.0
# A picture is one flat colour when no pixel's 8-bit RGB is more than this many display steps
# from another's: a one-step dither is invisible, a gradient background or a lit sphere is not.
FLAT_STEPS = 1


def verdict(c: Comparison) -> str:
    """One frame's place on the scale (the module docstring)."""
    if c.match:
        return SAME
    if c.nan_mismatched_pixels == 0 and c.psnr_db >= CLOSE_PSNR_DB:
        return CLOSE
    return DIFFERENT


def worst(verdicts: Sequence[str]) -> str | None:
    """The worst verdict of the frames (None when there is none)."""
    return max(verdicts, key=VERDICTS.index) if verdicts else None


def nonfinite_pixels(img: np.ndarray) -> int:
    """Pixels with a NaN or Inf in a colour channel (alpha is forced to 1 in the Image pass)."""
    return int((~np.isfinite(np.asarray(img)[..., :3])).any(axis=-1).sum())


def is_flat(img: np.ndarray) -> bool:
    """Whether the picture, as the screen shows it, is one colour (within FLAT_STEPS)."""
    q = quantise(np.asarray(img)[..., :3]).reshape(-1, 3).astype(np.int16)
    return bool(q.size) and int((q.max(axis=0) - q.min(axis=0)).max()) <= FLAT_STEPS


def _shown(img: np.ndarray) -> np.ndarray:
    """RGB as the screen shows it (compare's display values: NaN 0, +Inf 1, clamped)."""
    rgb = np.asarray(img, dtype=np.float32)[..., :3]
    return np.clip(np.nan_to_num(rgb, nan=0.0, posinf=1.0, neginf=0.0), 0.0, 1.0)


def animates(images: Sequence[np.ndarray]) -> bool | None:
    """Whether the frames (at different times) differ anywhere by more than verify's display
    tolerance; None for fewer than two frames."""
    if len(images) < 2:
        return None
    first = _shown(images[0])
    return any(float(np.abs(_shown(img) - first).max()) > DEFAULT_ABS_TOL for img in images[1:])
