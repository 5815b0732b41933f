"""`verify --against webgl`: NumPy against WebGL, with the pixels that depend on the driver set
apart.

Two real drivers do not agree on every pixel: SwiftShader (under ANGLE, in the browser) and
Mesa's llvmpipe compute `pow`, `exp2`, `log2`, `sin` ... with different float32 approximations,
all within what GLSL ES allows, and a highlight `pow(x, 64.0)` or a hash turns those last bits
into visible differences. Such a pixel has no single right value, so holding the NumPy renderer to
one driver there would fail it for the driver's choice. Each frame is therefore rendered three
times with the same inputs (NumPy, WebGL, GL):

- `drivers` compares GL with WebGL (`compare.compare`, the verify tolerance model); its
  over-tolerance pixels are the *driver-dependent* pixels.
- The verdict compares NumPy with WebGL where the drivers agree and, at a driver-dependent pixel,
  with whichever driver's value is closer to NumPy's (a pixel passes if NumPy agrees with one
  real driver). Everywhere else the model is unchanged, so a NumPy bug still fails: a wrong
  value matches neither driver.
- `plain` is NumPy against WebGL alone, kept for the numbers.
- A frame that fails in a program that reads undefined values sets apart, in the verdict and
  in `plain`, the pixels whose NumPy colour changes with those values (verify.UndefinedSide):
  WebGL zero-initialises variables as the NumPy renderer does, but an operation on constants
  outside its range is each driver's own.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from .compare import Comparison, compare
from .verify import (
    BACKENDS,
    FrameResult,
    UndefinedSide,
    _as_shader,
    _Pair,
    compile_backend,
    emulate_driver,
    engine_of,
    frame_specs,
)


@dataclass(eq=False)
class DriverFrameResult(FrameResult):
    """A FrameResult whose comparison is the driver-aware verdict, with its two ingredients."""

    plain: Comparison | None = None  # NumPy against WebGL alone
    drivers: Comparison | None = None  # GL against WebGL
    driver_image: np.ndarray | None = None  # the GL render (kept with keep_images)

    @property
    def driver_pixels(self) -> int:
        """Pixels over tolerance between the two drivers."""
        d = self.drivers
        return 0 if d is None else int(d.mismatched_pixels + d.edge_pixels)


def closest_driver(
    numpy_img: np.ndarray, webgl_img: np.ndarray, gl_img: np.ndarray, driver_mask: np.ndarray
) -> np.ndarray:
    """WebGL's image with each driver-dependent pixel taken from whichever driver is closer to
    NumPy (max abs difference over RGB; a NaN in both, or the same infinity in both, is no
    difference, as `compare` counts them; a NaN in one only is as far as possible)."""
    ref = numpy_img[..., :3].astype(np.float64)

    def distance(img):
        got = img[..., :3].astype(np.float64)
        with np.errstate(invalid="ignore"):
            d = np.abs(got - ref)
        d[(got == ref) | (np.isnan(got) & np.isnan(ref))] = 0.0
        return np.nan_to_num(d, nan=np.inf).max(axis=-1)

    take_gl = driver_mask & (distance(gl_img) < distance(webgl_img))
    return np.where(take_gl[..., None], gl_img, webgl_img)


def driver_verdict(
    numpy_img, webgl_img, gl_img, undefined=None, **compare_options
) -> tuple[Comparison, Comparison, Comparison]:
    """(verdict, plain, drivers) for one frame; see the module docstring. `undefined`: the
    pixels that depend on undefined values (compare's step 8), set apart in verdict and plain."""
    drivers = compare(gl_img, webgl_img, **compare_options)
    plain = compare(numpy_img, webgl_img, undefined=undefined, **compare_options)
    assert drivers.error_map is not None  # compare() fills it
    mask = np.asarray(drivers.error_map > drivers.abs_tol)
    if not mask.any() or plain.match:
        return plain, plain, drivers
    verdict = compare(
        numpy_img,
        closest_driver(numpy_img, webgl_img, gl_img, mask),
        undefined=undefined,
        **compare_options,
    )
    return verdict, plain, drivers


def verify_against_webgl(
    shader,
    *,
    size=(800, 450),
    sizes=None,
    time=None,
    times=None,
    frames=None,
    fps=None,
    frame=None,
    mouse=(0.0, 0.0, 0.0, 0.0),
    date=None,
    precision: str = "float32",
    samples: int = 1,
    keep_images: bool = False,
    compare_options: dict | None = None,
    progress=None,
    programs=None,
) -> Iterator[DriverFrameResult]:
    """`verify.verify_frames` for the pair (the default CPU program, webgl), each frame also
    rendered by GL.

    `programs` = (numpy, webgl, gl) compiled programs instead of compiling them here (the
    drivers first, so a missing browser or context is reported before the NumPy transpile).
    """
    specs = frame_specs(time, times, frames, fps, frame)
    shader = _as_shader(shader)
    if programs is None:
        webgl = compile_backend(shader, "webgl")
        gl = compile_backend(shader, "gl")
        programs = (compile_backend(shader, BACKENDS[0]), webgl, gl)
    emulate_driver([programs[0], programs[2]])  # the NumPy side copies the measured GL driver
    pair = _Pair(programs)
    undefined = UndefinedSide(shader, programs, numpy_under_test=True)
    name = shader.root or (shader.image.path if shader.image else "<shader>")
    options = compare_options or {}
    for w_h in [tuple(s) for s in (sizes or [size])]:
        for spec in specs:
            with undefined.explains_stops():
                numpy_img, webgl_img, gl_img = pair.render(
                    spec, w_h, tuple(mouse), date, precision, samples
                )
            verdict, plain, drivers = driver_verdict(numpy_img, webgl_img, gl_img, **options)
            if not verdict.match:
                inputs = pair.inputs(spec, w_h, tuple(mouse), date, precision, samples)
                mask = undefined.mask(inputs, numpy_img)
                if mask is not None:
                    verdict, plain, drivers = driver_verdict(
                        numpy_img, webgl_img, gl_img, undefined=mask, **options
                    )
                    # compare sets the mask of the pixels it counts
                    if verdict.undefined_pixels and verdict.undefined_mask is not None:
                        verdict.undefined_lines = undefined.lines(inputs, verdict.undefined_mask)
            if progress is not None:
                progress.step(f"{name} t={spec.time:g}")
            kept = (numpy_img, webgl_img, gl_img) if keep_images else (None, None, None)
            yield DriverFrameResult(
                name,
                spec,
                (int(w_h[0]), int(w_h[1])),
                verdict,
                kept[0],
                kept[1],
                engine=engine_of(programs[0], BACKENDS[0]),
                plain=plain,
                drivers=drivers,
                driver_image=kept[2],
            )
