"""Comparing a NumPy (CPU) render with an OpenGL render: the metrics, the tolerance model, the diff
image.

This module owns the verdict of `verify`: when two float images of one shader count as "the same
picture". The tolerance model, step by step (every number is argued where it is defined):

1. **Only RGB is compared.** The Image pass forces alpha to 1 in both renderers, so alpha
   carries nothing (`include_alpha=True` compares it too, for buffer passes).
2. **NaN and Inf are found before anything else**, per channel. NaN in both images, or the same
   infinity in both, counts as equal: both renderers computed the same undefined thing. A
   non-finite value in one image only (or NaN against Inf, or +Inf against -Inf) is a *NaN
   mismatch*: such a pixel always fails, whatever the budgets, because it means one renderer
   took a different path through undefined behaviour (`normalize(vec3(0))`, `pow(-x, y)`, ...),
   which the CPU renderer has to copy exactly. In the metrics that channel counts as an error
   of 1.0 (the whole display range).
3. **Values are clamped to [0, 1] before differencing**, since that is what Shadertoy shows:
   the canvas is 8-bit, so 3.5 and 3.6 are the same white, and a difference the viewer cannot
   see is not a failure. (NaN/Inf were handled in step 2, before the clamp could hide them.)
4. **A pixel is over tolerance** when any channel differs by more than `abs_tol` = 2/255.
   The display quantises to steps of 1/255; two float values that differ by a tiny amount can
   still round to neighbouring steps, so one step is noise, and the second step absorbs what
   GLSL itself leaves open: highp is float32 but compilers may reassociate, fuse multiply-adds
   and use reciprocals, and `exp2`, `log2`, `pow`, `sin` ... carry ULP-level (or for `sin`,
   unspecified) error that a long chain of arithmetic grows to ~1e-3. Below 2/255 the two 8-bit
   PNGs differ by at most two levels, which no one sees.
5. **Edge pixels** are over-tolerance pixels at a discontinuity that a sub-pixel shift
   explains: (a) the value jumps within the 3x3 neighbourhood (max - min of an over-tolerance
   channel > `edge_threshold` = 0.1 in either image), and (b) the shift works both ways: the
   NumPy colour at p lies between the GL colours at p and at some neighbour q, and the GL
   colour at p lies between the NumPy colours at p and at some neighbour q', in every
   over-tolerance channel at once (within `abs_tol`): moving the sample point a little turns
   each picture into the other there. That is a silhouette, a branch boundary
   (`if (d < 0.0)`) or a thresholded hash (`step(0.5, hash(p))`) where one float32 rounding
   flips a comparison. A wrong colour fails (b), even on an outline or one pixel thin, since
   the other image has no such colour nearby.
   0.1 is 25 display levels across two pixels: far steeper than smooth shading at 800x450 (a
   full-range gradient across the image changes by ~1/800 per pixel), so smooth regions never
   count as edges. A continuous hash (`fract(sin(x) * 43758.5453)`) that comes out different
   everywhere fails as mismatches, which is right: the CPU renderer must then copy the GPU's
   float32 `sin`, and the report says so instead of the tolerance widening for every shader.
   Edge pixels are counted apart (`edge_pixels`) and allowed up to `edge_fraction` = 0.5% of
   the pixels: 1800 at 800x450, the whole outline of a large object (a circle of radius 280
   has a 1760-pixel perimeter), while a rounding flip touches only a few outline pixels.
6. **Other over-tolerance pixels** (`mismatched_pixels`, NaN mismatches included) are allowed up
   to `(1 - min_fraction)` of the pixels, with `min_fraction` = 0.999: 360 scattered pixels at
   800x450 (a raymarcher that takes one step more at a grazing angle). A 20x20 block of wrong
   colour is 400 pixels, so a real local bug still fails.

   match = mismatched <= (1 - min_fraction) * pixels  and  edges <= edge_fraction * pixels
           and no NaN mismatch.

7. **Unstable pixels** (with `reference`, the float64 render of the same frame, which `verify`
   adds when a frame fails steps 1-6): an over-tolerance pixel where BOTH float32 renders are
   more than `abs_tol` from the float64 value (or non-finite where it is not) is ill-conditioned
   in float32 (a camera 2000 units from a unit sphere, `b*b - c` cancelling): it is counted in
   `unstable_pixels` and left out of the budgets. The verdict is then "match-unstable" (JSON
   `"verdict"`; `"match"` stays true). A pixel where only the NumPy render strays from the
   reference is still a mismatch: a transpiler bug cannot hide here.

8. **Undefined pixels** (with `undefined`, a mask `verify` makes when the program reads a value
   GLSL leaves undefined: `semantics.analysis.undefined`): an over-tolerance pixel whose NumPy
   colour itself changes when the undefined values change (`depends_on_undefined`) is the
   shader's undefined behaviour, not a renderer's fault: it is counted in `undefined_pixels`,
   left out of every other count, and `undefined_lines` names the reads. When such pixels are
   the only difference the verdict is "undefined" (`"match"` false: the renders differ, and
   the shader is at fault).

Metrics (`max_abs_error`, `mean_abs_error`, `psnr_db`) are over the clamped RGB values. Where
the differences lie is kept too: the bounding box of over-tolerance pixels and the worst pixels,
each in image space (x, y from the top-left, as in the PNG) and in fragCoord space (pixel
centre, y from the bottom: (x + 0.5, height - y - 0.5)), which is what a shader author needs.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, field

import numpy as np

DEFAULT_ABS_TOL = 2.0 / 255.0
DEFAULT_MIN_FRACTION = 0.999
DEFAULT_EDGE_THRESHOLD = 0.1
DEFAULT_EDGE_FRACTION = 0.005
WORST_PIXELS = 10

JSON_KEYS = (
    "match",
    "verdict",
    "size",
    "max_abs_error",
    "mean_abs_error",
    "psnr_db",
    "mismatched_pixels",
    "edge_pixels",
    "nan_numpy",
    "nan_gl",
    "unstable_pixels",
    "unstable_lines",
    "undefined_pixels",
    "undefined_lines",
    "driver",
)

# Diff image colours (RGB 0-255).
EDGE_COLOUR = (0, 200, 255)  # cyan-blue: an over-tolerance pixel explained by a discontinuity
NAN_COLOUR = (255, 0, 255)  # magenta: NaN/Inf in one image only


@dataclass(frozen=True, slots=True)
class PixelDiff:
    """One differing pixel: image coords (x, y from top-left) and the matching fragCoord."""

    x: int
    y: int
    frag_coord: tuple[float, float]
    numpy: tuple[float, ...]
    gl: tuple[float, ...]
    error: float
    kind: str  # "mismatch" | "edge" | "nan" | "undefined"


@dataclass(eq=False)
class Comparison:
    """The outcome of `compare`. `to_json()` gives the fixed summary; the rest is for people."""

    match: bool
    size: tuple[int, int]  # (width, height)
    max_abs_error: float
    mean_abs_error: float
    psnr_db: float  # math.inf when the clamped images are identical
    mismatched_pixels: int
    edge_pixels: int
    nan_numpy: int
    nan_gl: int
    nan_mismatched_pixels: int = 0
    max_abs_error_unclamped: float = 0.0  # over channels finite in both images
    bbox: tuple[int, int, int, int] | None = (
        None  # x0, y0, x1, y1 (exclusive) of over-tolerance pixels
    )
    worst: list[PixelDiff] = field(default_factory=list)
    abs_tol: float = DEFAULT_ABS_TOL
    mismatch_budget: float = 0.0
    edge_budget: float = 0.0
    # Per-pixel maps (height, width) for the diff image.
    error_map: np.ndarray | None = field(default=None, repr=False)
    edge_mask: np.ndarray | None = field(default=None, repr=False)
    nan_mask: np.ndarray | None = field(default=None, repr=False)
    # Unstable pixels (step 7): over tolerance, but both float32 renders are far from the
    # float64 reference there; counted apart, not as mismatches.
    unstable_pixels: int = 0
    unstable_mask: np.ndarray | None = field(default=None, repr=False)
    # [{"file", "line", "code", "bits", "pixels"}]: the statements where the unstable pixels
    # lose their precision, filled in by verify.unstable_lines (glslcheck probe's tracing).
    unstable_lines: list = field(default_factory=list)
    # Undefined pixels (step 8): over tolerance, and their colour depends on a value GLSL
    # leaves undefined; [{"file", "line", "column", "code", "kind", "pixels"}] names the reads
    # (filled in by verify.undefined_side).
    undefined_pixels: int = 0
    undefined_mask: np.ndarray | None = field(default=None, repr=False)
    undefined_lines: list = field(default_factory=list)
    # {"renderer", "mesa", "emulated"} of the GL side, set by verify (None: not a GL driver);
    # "emulated" is false when the NumPy backend's bit-exact emulation was not copied from it
    # (glslcheck/backends/driver_profile.py): a difference may then be the driver's.
    driver: dict | None = None

    # set by compare: the frame matches once undefined pixels are set apart (step 8)
    rest_matches: bool = True

    @property
    def verdict(self) -> str:
        """ "match", "match-unstable" (a match only once unstable pixels are set apart),
        "undefined" (the only differences are pixels that depend on undefined values) or
        "mismatch"."""
        if not self.match:
            return "undefined" if self.undefined_pixels and self.rest_matches else "mismatch"
        return "match-unstable" if self.unstable_pixels else "match"

    def to_json(self) -> dict:
        """Exactly the keys in JSON_KEYS; psnr_db is null for identical images (JSON has no inf)."""
        return {
            "match": bool(self.match),
            "verdict": self.verdict,
            "size": [int(self.size[0]), int(self.size[1])],
            "max_abs_error": float(self.max_abs_error),
            "mean_abs_error": float(self.mean_abs_error),
            "psnr_db": None if math.isinf(self.psnr_db) else float(self.psnr_db),
            "mismatched_pixels": int(self.mismatched_pixels),
            "edge_pixels": int(self.edge_pixels),
            "nan_numpy": int(self.nan_numpy),
            "nan_gl": int(self.nan_gl),
            "unstable_pixels": int(self.unstable_pixels),
            "unstable_lines": list(self.unstable_lines),
            "undefined_pixels": int(self.undefined_pixels),
            "undefined_lines": list(self.undefined_lines),
            "driver": dict(self.driver) if self.driver is not None else None,
        }

    def dumps(self) -> str:
        return json.dumps(self.to_json())

    def summary(self) -> str:
        """One human line: verdict, counts against budgets, and where the worst pixel is."""
        verdict = {"match": "match", "match-unstable": "match", "undefined": "UNDEFINED"}.get(
            self.verdict, "MISMATCH"
        )
        psnr = "inf" if math.isinf(self.psnr_db) else f"{self.psnr_db:.1f}"
        text = (
            f"{verdict}: max abs error {self.max_abs_error:.4g}, PSNR {psnr} dB, "
            f"{self.mismatched_pixels} mismatched (budget {int(self.mismatch_budget)}), "
            f"{self.edge_pixels} edge (budget {int(self.edge_budget)}), "
            f"NaN/Inf numpy {self.nan_numpy} gl {self.nan_gl}"
        )
        if self.undefined_pixels:
            text += f", {self.undefined_pixels} undefined in the shader"
        if self.worst:
            w = self.worst[0]
            text += (
                f"; worst at pixel ({w.x}, {w.y}) = fragCoord ({w.frag_coord[0]}, "
                f"{w.frag_coord[1]}): numpy {_fmt(w.numpy)} gl {_fmt(w.gl)}"
            )
        return text


def _fmt(values: tuple[float, ...]) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in values) + ")"


def _as_float(img: np.ndarray) -> np.ndarray:
    """float64 (h, w, c); 8-bit images (e.g. read from PNG) are scaled to [0, 1]."""
    img = np.asarray(img)
    if img.ndim == 2:
        img = img[..., None]
    if img.ndim != 3:
        raise ValueError(f"an image must be (height, width, channels), not shape {img.shape}")
    if img.dtype == np.uint8:
        return img.astype(np.float64) / 255.0
    return img.astype(np.float64)


_NEIGHBOURS = [(dy, dx) for dy in (-1, 0, 1) for dx in (-1, 0, 1) if (dy, dx) != (0, 0)]


def _between(x, y, yq, tol, channels) -> np.ndarray:
    """Per candidate pixel: x within [min(y, yq), max(y, yq)] (+-tol) in every channel selected."""
    inside = (x >= np.minimum(y, yq) - tol) & (x <= np.maximum(y, yq) + tol)
    return (inside | ~channels).all(axis=-1)


def _display(values: np.ndarray) -> np.ndarray:
    """What the screen shows: NaN as 0, +Inf as 1, -Inf as 0, everything clamped to [0, 1]."""
    return np.clip(np.nan_to_num(values, nan=0.0, posinf=1.0, neginf=0.0), 0.0, 1.0)


def compare(
    numpy_img: np.ndarray,
    gl_img: np.ndarray,
    *,
    abs_tol: float = DEFAULT_ABS_TOL,
    min_fraction: float = DEFAULT_MIN_FRACTION,
    edge_threshold: float = DEFAULT_EDGE_THRESHOLD,
    edge_fraction: float = DEFAULT_EDGE_FRACTION,
    include_alpha: bool = False,
    reference: np.ndarray | None = None,
    undefined: np.ndarray | None = None,
) -> Comparison:
    """Compare two renders of one shader (float (h, w, 3|4), top row first) by the module's model.

    `reference` (the float64 render of the same frame) enables step 7: unstable pixels;
    `undefined` (bool (h, w): pixels whose colour depends on an undefined value) step 8."""
    a, b = _as_float(numpy_img), _as_float(gl_img)
    if a.shape[:2] != b.shape[:2]:
        raise ValueError(
            f"the images differ in size: numpy {a.shape[1]}x{a.shape[0]}, "
            f"gl {b.shape[1]}x{b.shape[0]}"
        )
    channels = min(a.shape[2], b.shape[2], 4 if include_alpha else 3)
    a, b = a[..., :channels], b[..., :channels]
    height, width = a.shape[:2]
    pixels = height * width

    # Step 2: non-finite values, per channel, before any clamping.
    fin_a, fin_b = np.isfinite(a), np.isfinite(b)
    with np.errstate(invalid="ignore"):
        same_special = ~fin_a & ~fin_b & ((np.isnan(a) & np.isnan(b)) | (a == b))
    special_mismatch = (~fin_a | ~fin_b) & ~same_special
    nan_mask = special_mismatch.any(axis=-1)

    # Step 3: displayed values and their differences.
    da, db = _display(a), _display(b)
    diff = np.abs(da - db)
    diff[same_special] = 0.0
    diff[special_mismatch] = 1.0
    error_map = diff.max(axis=-1)

    # Step 4: over tolerance, per channel and per pixel.
    over_ch = diff > abs_tol
    over = over_ch.any(axis=-1)

    # Step 5: an over-tolerance pixel is an edge when the neighbourhood jumps and a sub-pixel
    # shift explains it both ways: a(p) lies between b(p) and b at some neighbour, and b(p)
    # between a(p) and a at some neighbour, in every over-tolerance channel at once.
    # Only the candidate pixels are examined, so a near-identical pair compares quickly.
    edge_mask = np.zeros((height, width), dtype=bool)
    ys, xs = np.nonzero(over & ~nan_mask)
    if len(ys):
        cand_over = over_ch[ys, xs]
        pa, pb = da[ys, xs], db[ys, xs]
        lo_a, hi_a, lo_b, hi_b = pa.copy(), pa.copy(), pb.copy(), pb.copy()
        a_explained = np.zeros(len(ys), dtype=bool)  # a(p) lies between b(p) and some b(q)
        b_explained = np.zeros(len(ys), dtype=bool)  # b(p) lies between a(p) and some a(q)
        for dy, dx in _NEIGHBOURS:
            qy, qx = np.clip(ys + dy, 0, height - 1), np.clip(xs + dx, 0, width - 1)
            qa, qb = da[qy, qx], db[qy, qx]
            lo_a, hi_a = np.minimum(lo_a, qa), np.maximum(hi_a, qa)
            lo_b, hi_b = np.minimum(lo_b, qb), np.maximum(hi_b, qb)
            a_explained |= _between(pa, pb, qb, abs_tol, cand_over)
            b_explained |= _between(pb, pa, qa, abs_tol, cand_over)
        steep = ((np.maximum(hi_a - lo_a, hi_b - lo_b) > edge_threshold) & cand_over).any(axis=-1)
        edge_mask[ys, xs] = steep & a_explained & b_explained
    mismatch_mask = over & ~edge_mask  # NaN mismatches included

    # Step 7: unstable pixels. Where both float32 renders are more than abs_tol away from the
    # float64 reference (displayed values, or a NaN/Inf the reference does not have), float32
    # itself cannot compute the pixel: the two renderers rounding differently is not a bug.
    # A pixel where only the NumPy render strays from the reference stays a mismatch.
    unstable = np.zeros((height, width), dtype=bool)
    if reference is not None:
        r = _as_float(reference)[..., :channels]
        dr = _display(r)
        fin_r = np.isfinite(r)
        far_a = (np.abs(da - dr) > abs_tol) | (fin_a != fin_r)
        far_b = (np.abs(db - dr) > abs_tol) | (fin_b != fin_r)
        unstable = (over_ch & far_a & far_b).any(axis=-1) & over
        mismatch_mask &= ~unstable
        nan_mask = nan_mask & ~unstable
        edge_mask &= ~unstable

    # Step 8: pixels whose colour depends on a value GLSL leaves undefined: the shader's fault,
    # whatever else they are.
    undef = np.zeros((height, width), dtype=bool)
    if undefined is not None:
        undef = over & np.asarray(undefined, dtype=bool)
        mismatch_mask &= ~undef
        nan_mask = nan_mask & ~undef
        edge_mask &= ~undef
        unstable &= ~undef

    mismatched = int(mismatch_mask.sum())
    edges = int(edge_mask.sum())
    nan_mismatched = int(nan_mask.sum())
    mismatch_budget = (1.0 - min_fraction) * pixels
    edge_budget = edge_fraction * pixels
    rest_matches = mismatched <= mismatch_budget and edges <= edge_budget and nan_mismatched == 0
    # an undefined pixel is a difference (the renders disagree there): no match with any
    match = rest_matches and not undef.any()

    mse = float(np.mean(diff**2)) if diff.size else 0.0
    psnr = math.inf if mse == 0.0 else 10.0 * math.log10(1.0 / mse)
    both_finite = fin_a & fin_b
    with np.errstate(invalid="ignore", over="ignore"):
        unclamped = float(np.abs(np.where(both_finite, a - b, 0.0)).max()) if a.size else 0.0

    bbox = None
    if over.any():
        ys, xs = np.nonzero(over)
        bbox = (int(xs.min()), int(ys.min()), int(xs.max()) + 1, int(ys.max()) + 1)

    return Comparison(
        match=bool(match),
        size=(width, height),
        max_abs_error=float(error_map.max()) if error_map.size else 0.0,
        mean_abs_error=float(diff.mean()) if diff.size else 0.0,
        psnr_db=psnr,
        mismatched_pixels=mismatched,
        edge_pixels=edges,
        nan_numpy=int((~fin_a).any(axis=-1).sum()),
        nan_gl=int((~fin_b).any(axis=-1).sum()),
        nan_mismatched_pixels=nan_mismatched,
        max_abs_error_unclamped=unclamped,
        bbox=bbox,
        worst=_worst_pixels(a, b, error_map, over, edge_mask, nan_mask, undef),
        abs_tol=abs_tol,
        mismatch_budget=mismatch_budget,
        edge_budget=edge_budget,
        error_map=error_map.astype(np.float32),
        edge_mask=edge_mask,
        nan_mask=nan_mask,
        unstable_pixels=int(unstable.sum()),
        unstable_mask=unstable,
        undefined_pixels=int(undef.sum()),
        undefined_mask=undef,
        rest_matches=bool(rest_matches),
    )


def depends_on_undefined(
    zero: np.ndarray, varied: np.ndarray, abs_tol: float = DEFAULT_ABS_TOL
) -> np.ndarray:
    """bool (h, w): the pixels whose RGB differs between two renders of one program that differ
    only in the values of its undefined reads (WebGL's zeros, and values drawn anew: the NumPy
    backend's undefined="vary"), by the tolerance of step 4 or in being finite. Such a pixel
    depends on the undefined values: a witness, never a guess (nothing else changed between
    the renders); a pixel both values happen to colour alike is not found."""
    a, b = _as_float(zero)[..., :3], _as_float(varied)[..., :3]
    with np.errstate(invalid="ignore"):
        special = np.isfinite(a) != np.isfinite(b)
        special |= ~np.isfinite(a) & ~np.isfinite(b) & ~((np.isnan(a) & np.isnan(b)) | (a == b))
    return ((np.abs(_display(a) - _display(b)) > abs_tol) | special).any(axis=-1)


def _worst_pixels(
    a, b, error_map, over, edge_mask, nan_mask, undef, count: int = WORST_PIXELS
) -> list[PixelDiff]:
    """The over-tolerance pixels with the largest error, worst first (NaN mismatches first of
    all)."""
    ys, xs = np.nonzero(over)
    if len(ys) == 0:
        return []
    score = error_map[ys, xs] + 2.0 * nan_mask[ys, xs]  # NaN mismatches sort before everything
    order = np.argsort(-score, kind="stable")[:count]
    height = error_map.shape[0]
    out = []
    for i in order:
        y, x = int(ys[i]), int(xs[i])
        kind = (
            "undefined"
            if undef[y, x]
            else "nan"
            if nan_mask[y, x]
            else "edge"
            if edge_mask[y, x]
            else "mismatch"
        )
        out.append(
            PixelDiff(
                x=x,
                y=y,
                frag_coord=(x + 0.5, height - y - 0.5),
                numpy=tuple(float(v) for v in a[y, x]),
                gl=tuple(float(v) for v in b[y, x]),
                error=float(error_map[y, x]),
                kind=kind,
            )
        )
    return out


def heat_colours(error: np.ndarray) -> np.ndarray:
    """uint8 RGB for errors in [0, 1]: black -> red -> yellow -> white.

    The square root spreads the small errors that matter (2/255 is already a visible dark red,
    0.1 a clear red) while a full-range error is white.
    """
    t = np.sqrt(np.clip(np.nan_to_num(error, nan=1.0), 0.0, 1.0)) * 3.0
    rgb = np.stack([np.clip(t, 0, 1), np.clip(t - 1, 0, 1), np.clip(t - 2, 0, 1)], axis=-1)
    return (rgb * 255.0 + 0.5).astype(np.uint8)


def diff_colours(comp: Comparison) -> np.ndarray:
    """The diff image of a comparison as uint8 RGB: `heat_colours` of the per-pixel error, edge
    pixels in EDGE_COLOUR, NaN/Inf in one image only in NAN_COLOUR."""
    if comp.error_map is None:
        raise ValueError("this Comparison carries no per-pixel maps")
    rgb = heat_colours(comp.error_map)
    rgb[comp.edge_mask] = EDGE_COLOUR
    rgb[comp.nan_mask] = NAN_COLOUR
    return rgb


def write_diff_png(comparison_or_imgs, path: str | os.PathLike) -> Comparison:
    """Write the heat map of per-pixel max abs difference; returns the Comparison used.

    Accepts a `Comparison` or a pair `(numpy_img, gl_img)` (compared with the defaults).
    Black = equal, through red and yellow to white = full-range error; over-tolerance pixels
    explained by a discontinuity are cyan-blue, NaN/Inf in one image only magenta.
    Same size as the renders, row 0 at the top.
    """
    from ..base.images import save_rgb

    comp = comparison_or_imgs
    if not isinstance(comp, Comparison):
        numpy_img, gl_img = comparison_or_imgs
        comp = compare(numpy_img, gl_img)
    save_rgb(
        diff_colours(comp), path, "diff image"
    )  # atomic; InputError (exit 2) when it cannot be written
    return comp
