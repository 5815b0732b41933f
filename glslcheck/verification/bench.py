"""Time against error: how fast each way of rendering a shader is, and how far from the truth.

This module owns the `bench` measurement: which configurations are rendered, how they are
timed, the reference they are measured against, the Pareto front, the text table and the
time-against-error plot. The error metrics themselves come from `glslcheck.verification.compare`.

Library API:

    rows = bench_shader("lab_shaders/07_final", size=(400, 225), runs=3)
    print(format_table(rows))
    write_plot(rows, "accuracy.png")
    [row.to_json() for row in rows]          # exactly the keys in JSON_KEYS

Configurations (`configurations()`): the GL driver (highp = float32) and the default CPU program
at float16, float32 and float64, each at 1, 4 and 16 samples per pixel (a 1x1, 2x2, 4x4 sub-pixel
grid, the same on both backends): 12 per shader. The default CPU program is the NumPy backend,
whose float32 frames move to the compiled engine once they have cost its compile, where that
gives the same bits (backends/tiered.py); each row says which engine rendered its timed rounds
("numpy", "compiled lanes8", or both in order, "numpy then compiled lanes8"); with
`compiled=True` also the compiled engine alone (glslcheck/compiled_backend, float32; its first
render loads or compiles its module, so that time is in the warm-up, not in the timed rounds),
and with `webgl=True` WebGL 2.

Timing: one warm-up render per configuration (it compiles the GL supersampling variant and
executes the NumPy module for that precision), then `runs` rounds in which every configuration
renders once, round-robin, so background load on a shared machine falls on all of them alike;
a configuration's time is the median of its rounds. A render is the whole `Program.render`
call: uniforms, every sample, averaging, and the float32 image back in memory (for GL also the
framebuffer read-back). The NumPy backend keeps a cache of frames for shaders that do not
animate; it is emptied before every timed NumPy render, so each one really renders. NumPy
renders on worker processes where available (glslcheck/backends/numpy_engine/workers.py), all of
them: GLSLCHECK_PARALLEL=threads times threads instead.
`ratio_to_gl` is a configuration's time over the time of GL at 1 sample of the same shader,
measured in the same run.

Error (`measure_error`): against the reference, NumPy float64 at 16 samples per pixel, on RGB
(alpha is 1 in the Image pass) as the screen shows it: NaN as 0, +Inf as 1, values clamped to
[0, 1]; a NaN/Inf in one image only counts as an error of 1. This is `compare.compare`, so the
numbers mean what `verify` reports: `max_abs_error` and `mean_abs_error` over the RGB channels,
`psnr_db` over the same (inf for identical images: null in JSON), and `pixels_over_1_255`: the
pixels where some RGB channel differs by more than 1/255, one step of the 8-bit display.
"""

from __future__ import annotations

import math
import os
import statistics
import time as _time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..backends import registry
from ..base.precision import PRECISIONS
from ..shadertoy.sources import Shader, load_shader
from .compare import compare
from .verify import engine_of

SAMPLES = (1, 4, 16)
REFERENCE = (registry.DEFAULT, "float64", 16)  # backend, precision, samples (NumPy's frames)
DEFAULT_SIZE = (400, 225)
DEFAULT_RUNS = 3
ONE_STEP = 1.0 / 255.0

JSON_KEYS = (
    "shader",
    "backend",
    "precision",
    "samples",
    "median_ms",
    "ratio_to_gl",
    "max_abs_error",
    "mean_abs_error",
    "psnr_db",
    "pixels_over_1_255",
    "engine",
)


@dataclass(frozen=True, slots=True)
class Config:
    """One way of rendering: backend (a name of `registry.names()`), float precision, samples per
    pixel."""

    backend: str
    precision: str
    samples: int

    @property
    def label(self) -> str:
        """Short name for tables and plots: 'gl x4', 'f16 x16'."""
        several = (
            len(registry.get(self.backend).precisions) > 1
        )  # the NumPy engine: named by its precision
        name = "f" + self.precision.removeprefix("float") if several else self.backend
        return f"{name} x{self.samples}"

    @property
    def is_reference(self) -> bool:
        return (self.backend, self.precision, self.samples) == REFERENCE


def configurations(
    samples: Sequence[int] = SAMPLES, webgl: bool = False, compiled: bool = False
) -> list[Config]:
    """GL first (its one-sample time is the unit of `ratio_to_gl`), then WebGL (headless
    Chromium) and the compiled engine (when asked for), then NumPy by precision."""
    configs = [Config("gl", "float32", s) for s in samples]
    configs += [Config("webgl", "float32", s) for s in samples if webgl]
    configs += [Config("compiled", "float32", s) for s in samples if compiled]
    configs += [Config(registry.DEFAULT, p, s) for p in PRECISIONS for s in samples]
    return configs


@dataclass(eq=False)
class Row:
    """One configuration of one shader: its timing and its error against the reference."""

    shader: str
    config: Config
    median_ms: float
    ratio_to_gl: float
    max_abs_error: float
    mean_abs_error: float
    psnr_db: float  # math.inf when identical to the reference
    pixels_over_1_255: int
    times_ms: list[float] = field(default_factory=list)
    pareto: bool = False  # on the shader's Pareto front (no other row is both faster and closer)
    engine: str = ""  # the engines of its timed rounds, in order ("numpy then compiled lanes8")

    def to_json(self) -> dict:
        """Exactly JSON_KEYS; psnr_db is null when infinite (JSON has no inf)."""
        return {
            "shader": self.shader,
            "backend": self.config.backend,
            "precision": self.config.precision,
            "samples": int(self.config.samples),
            "median_ms": float(self.median_ms),
            "ratio_to_gl": float(self.ratio_to_gl),
            "max_abs_error": float(self.max_abs_error),
            "mean_abs_error": float(self.mean_abs_error),
            "psnr_db": None if math.isinf(self.psnr_db) else float(self.psnr_db),
            "pixels_over_1_255": int(self.pixels_over_1_255),
            "engine": self.engine or self.config.backend,
        }


def measure_error(image: np.ndarray, reference: np.ndarray) -> tuple[float, float, float, int]:
    """(max abs error, mean abs error, PSNR dB, pixels over 1/255) of RGB as displayed."""
    c = compare(image, reference, abs_tol=ONE_STEP)
    return c.max_abs_error, c.mean_abs_error, c.psnr_db, c.mismatched_pixels + c.edge_pixels


def _forget_frames(program) -> None:
    """Empty the NumPy backend's frame cache so the next render really renders."""
    cache = getattr(getattr(program, "impl", program), "_cache", None)
    if cache is not None:
        cache.clear()


def _pin_parallel(program) -> None:
    """Every NumPy configuration on the same kind of workers: "auto" would move to worker
    processes part-way through and mix the two in one table. A bench renders many frames, so
    it takes what "auto" moves to (processes, where available) unless GLSLCHECK_PARALLEL or
    the caller chose otherwise."""
    impl = getattr(program, "impl", program)
    if getattr(impl, "parallel", None) == "auto":
        from ..backends.numpy_engine import workers

        impl.parallel = "processes" if workers.available() else "threads"


def _compile_both(shader: Shader):
    """(gl, the default CPU program); GL first so a missing context is reported before a slow
    transpile."""
    gl = registry.compile(shader, backend="gl")
    return gl, registry.compile(shader, backend=registry.DEFAULT)


def bench_shader(
    shader,
    *,
    size: tuple[int, int] = DEFAULT_SIZE,
    runs: int = DEFAULT_RUNS,
    time: float = 0.0,
    samples: Sequence[int] = SAMPLES,
    programs: tuple | None = None,
    step: Callable[[str], None] | None = None,
    clock: Callable[[], float] = _time.perf_counter,
    webgl: bool = False,
    compiled: bool = False,
) -> list[Row]:
    """Time and measure every configuration of one shader (see the module docstring).

    `shader` is a path or a `Shader`; `programs` = (gl, the CPU program) compiled programs
    instead (a NumPy program is timed as the CPU rows).
    `step(label)` is called after each render (for a progress bar): `len(configurations())`
    times `runs + 1` calls. GlslError when the shader does not compile or a render fails,
    GLUnavailable (exit 2) without an OpenGL context.
    """
    if runs < 1:
        raise ValueError(f"runs must be at least 1, not {runs}")
    shader = shader if isinstance(shader, Shader) else load_shader(shader)
    name = shader.root or (shader.image.path if shader.image else "<shader>")
    gl, numpy_prog = programs if programs is not None else _compile_both(shader)
    _pin_parallel(numpy_prog)
    configs = configurations(samples, webgl, compiled)
    by_backend = {"gl": gl, registry.DEFAULT: numpy_prog}
    # WebGL 2 in headless Chromium; the compiled engine per pixel, by numba (InputError without
    # numba, GlslError for what it lacks)
    for backend in dict.fromkeys(c.backend for c in configs):
        if backend not in by_backend:
            by_backend[backend] = registry.compile(shader, backend=backend)
    kwargs = dict(size=tuple(size), time=float(time))

    engines: dict[Config, list[str]] = {c: [] for c in configs}

    def render(config: Config) -> tuple[np.ndarray, float]:
        program = by_backend[config.backend]
        if len(registry.get(config.backend).precisions) > 1:  # the precision is the configuration's
            _forget_frames(program)
            extra = {"precision": config.precision}
        else:
            extra = {}
        start = clock()
        image = program.render(**kwargs, samples=config.samples, **extra)
        took = (clock() - start) * 1000.0
        engines[config].append(engine_of(program, config.backend))
        return image, took

    images: dict[Config, np.ndarray] = {}
    times: dict[Config, list[float]] = {c: [] for c in configs}
    with warnings.catch_warnings():
        # float16 overflows on purpose (that is what is being measured): no warning per render.
        warnings.simplefilter("ignore", RuntimeWarning)
        for (
            config
        ) in configs:  # warm-up; renders are deterministic, so its image is the one measured
            images[config], _ = render(config)
            if step:
                step(f"{name} {config.label} warm-up")
        for r in range(runs):
            for config in configs:
                _, ms = render(config)
                times[config].append(ms)
                if step:
                    step(f"{name} {config.label} run {r + 1}/{runs}")
        reference = next((images[c] for c in configs if c.is_reference), None)
        if reference is None:
            _, precision, n = REFERENCE
            _forget_frames(numpy_prog)
            reference = numpy_prog.render(**kwargs, samples=n, precision=precision)

    medians = {c: statistics.median(times[c]) for c in configs}
    gl_one = next(
        (medians[c] for c in configs if c.backend == registry.REFERENCE_DRIVER and c.samples == 1),
        None,
    )
    rows = []
    for config in configs:
        max_err, mean_err, psnr, over = measure_error(images[config], reference)
        ratio = medians[config] / gl_one if gl_one else math.nan
        rows.append(
            Row(
                name,
                config,
                medians[config],
                ratio,
                max_err,
                mean_err,
                psnr,
                over,
                times[config],
                engine=" then ".join(dict.fromkeys(engines[config][1:])),
            )
        )
    mark_pareto(rows)
    return rows


def mark_pareto(rows: Sequence[Row]) -> list[Row]:
    """Set `pareto` on each shader's rows that no other row beats on both time and mean error.

    Returns the front of every shader, fastest first within a shader.
    """
    front: list[Row] = []
    for shader in dict.fromkeys(r.shader for r in rows):
        mine = sorted(
            (r for r in rows if r.shader == shader), key=lambda r: (r.median_ms, r.mean_abs_error)
        )
        best = math.inf
        for r in mine:
            r.pareto = r.mean_abs_error < best
            if r.pareto:
                best = r.mean_abs_error
                front.append(r)
    return front


# ---------------------------------------------------------------------------------------------
# Text table.

TABLE_NOTE = (
    "error: RGB as displayed (clamped to [0, 1]) against NumPy float64 at 16 samples per pixel;"
    " x GL@1: time over GL at 1 sample, same run; * = Pareto front (time, mean abs error)"
)
HEADER = (
    "config",
    "backend",
    "precision",
    "samples",
    "median ms",
    "x GL@1",
    "max abs err",
    "mean abs err",
    "PSNR dB",
    "px > 1/255",
    "front",
)


def _g(v: float) -> str:
    return "0" if v == 0 else f"{v:.3g}" if v >= 1e-3 else f"{v:.2e}"


def row_cells(r: Row) -> tuple[str, ...]:
    """A row's cells under HEADER, as the text table (and glslcheck report's table) shows them."""
    return (
        r.config.label,
        r.engine or r.config.backend,
        r.config.precision,
        str(r.config.samples),
        f"{r.median_ms:.1f}",
        f"{r.ratio_to_gl:.2f}",
        _g(r.max_abs_error),
        _g(r.mean_abs_error),
        "inf" if math.isinf(r.psnr_db) else f"{r.psnr_db:.1f}",
        str(r.pixels_over_1_255),
        "*" if r.pareto else "",
    )


def format_table(
    rows: Sequence[Row],
    size: tuple[int, int] | None = None,
    runs: int | None = None,
    time: float | None = None,
) -> str:
    """A table per shader; '*' in the last column marks the Pareto front (time against mean
    error)."""
    out = []
    for shader in dict.fromkeys(r.shader for r in rows):
        mine = [r for r in rows if r.shader == shader]
        head = shader
        if size:
            head += f"  {size[0]}x{size[1]}"
        if time is not None:
            head += f"  iTime {time:g}"
        if runs:
            head += f"  median of {runs} run{'s' if runs != 1 else ''}"
        out.append(head)
        cells = [HEADER] + [row_cells(r) for r in mine]
        widths = [max(len(row[i]) for row in cells) for i in range(len(HEADER))]
        for row in cells:
            parts = [
                c.ljust(w) if i in (0, 1, 2) else c.rjust(w)
                for i, (c, w) in enumerate(zip(row, widths))
            ]
            out.append("  " + "  ".join(parts).rstrip())
        out.append("")
    out.append(TABLE_NOTE)
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------------------------------------
# The plot: time (x, log) against mean abs error (y, log), one panel per shader. Pillow only.

COLOURS = {
    "gl": (40, 40, 40),
    "webgl": (148, 103, 189),
    "compiled": (140, 86, 75),
    "float16": (214, 39, 40),
    "float32": (31, 119, 180),
    "float64": (44, 160, 44),
}
FRONT_COLOUR = (255, 127, 14)
GRID = (225, 225, 225)
SCALE = 2  # drawn at twice the size, then downsampled: Pillow's shapes have no antialiasing


def _font(size: int):
    from PIL import ImageFont

    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow < 10.1: the fixed bitmap font
        return ImageFont.load_default()


def _colour_key(config: Config) -> str:
    """The key of COLOURS: the backend, or the precision for a backend that renders in several."""
    return config.precision if len(registry.get(config.backend).precisions) > 1 else config.backend


def _colour(config: Config) -> tuple[int, int, int]:
    return COLOURS[_colour_key(config)]


def _marker(draw, x: float, y: float, samples: int, colour, r: float) -> None:
    """1 sample: circle; 4: square; 16 (and more): diamond."""
    if samples <= 1:
        draw.ellipse(
            [x - r, y - r, x + r, y + r], fill=colour, outline=(255, 255, 255), width=SCALE
        )
    elif samples <= 4:
        q = r * 0.9
        draw.rectangle(
            [x - q, y - q, x + q, y + q], fill=colour, outline=(255, 255, 255), width=SCALE
        )
    else:
        q = r * 1.25
        draw.polygon(
            [(x, y - q), (x + q, y), (x, y + q), (x - q, y)], fill=colour, outline=(255, 255, 255)
        )


def _decades(lo: float, hi: float) -> tuple[int, int]:
    a, b = math.floor(math.log10(lo)), math.ceil(math.log10(hi))
    return (a, b) if b > a else (a, a + 1)


def _tick_text(e: int, unit: str = "") -> str:
    v = 10.0**e
    if -3 <= e <= 4:
        text = f"{v:g}"
    else:
        text = f"1e{e}"
    return text + unit


LEGEND_COLOURS = {
    "gl": "GL (llvmpipe, float32)",
    "webgl": "WebGL (ANGLE, SwiftShader)",
    "compiled": "compiled engine (numba, float32)",
    "float16": "NumPy float16",
    "float32": "NumPy float32",
    "float64": "NumPy float64",
}
LEGEND_SHAPES = ("1 sample", "4 samples", "16 samples", "Pareto front (ringed)")


def _legend_layout(text_widths: Sequence[float], width: int) -> list[tuple[float, int]]:
    """(x, row) of each legend item: left to right, wrapped to `width`."""
    S = SCALE
    out: list[tuple[float, int]] = []
    x: float = 20 * S
    row = 0
    for tw in text_widths:
        w = 20 * S + tw + 24 * S
        if x + w > width - 10 * S and x > 20 * S:
            x, row = 20 * S, row + 1
        out.append((x, row))
        x += w
    return out


def write_plot(rows: Sequence[Row], path: str | os.PathLike, title: str | None = None) -> None:
    """Write the PNG: per shader a panel of time against mean abs error, Pareto front drawn."""
    from PIL import Image, ImageDraw

    S = SCALE
    shaders = list(dict.fromkeys(r.shader for r in rows))
    if not shaders:
        raise ValueError("nothing to plot")
    pw, ph = 520 * S, 430 * S  # one panel
    left, right, top, bottom = 78 * S, 22 * S, 40 * S, 62 * S  # panel margins
    zero_gap = 26 * S  # the "0" row below the log axis, for rows identical to the reference
    title_h = (40 if len(shaders) >= 2 else 56) * S
    width = pw * len(shaders)
    f_title, f_axis, f_tick, f_label = _font(17 * S), _font(13 * S), _font(11 * S), _font(11 * S)
    measure = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    # every bench's colours, and those of the extra backends these rows have
    shown = {_colour_key(c) for c in configurations()} | {_colour_key(r.config) for r in rows}
    colour_keys = [k for k in LEGEND_COLOURS if k in shown]
    texts = [LEGEND_COLOURS[k] for k in colour_keys] + list(LEGEND_SHAPES)
    legend = _legend_layout([measure.textlength(t, font=f_axis) for t in texts], width)
    legend_h = (18 + 22 * (legend[-1][1] + 1)) * S
    height = title_h + ph + legend_h
    img = Image.new("RGB", (width, height), (255, 255, 255))
    draw = ImageDraw.Draw(img)

    title = title or "render time against error (reference: NumPy float64 at 16 samples)"
    if draw.textlength(title, font=f_title) > width - 20 * S and " (" in title:
        head, tail = title.split(" (", 1)
        title = head + "\n(" + tail
    draw.multiline_text(
        (width // 2, title_h // 2), title, font=f_title, fill=(0, 0, 0), anchor="mm", align="center"
    )

    # Shared axes: the same ranges in every panel, so panels compare at a glance.
    times = [r.median_ms for r in rows if r.median_ms > 0]
    errors = [r.mean_abs_error for r in rows if r.mean_abs_error > 0]
    tx0, tx1 = _decades(min(times), max(times)) if times else (0, 1)
    ey0, ey1 = _decades(min(errors), max(errors)) if errors else (-6, 0)

    for index, shader in enumerate(shaders):
        mine = [r for r in rows if r.shader == shader]
        ox, oy = index * pw, title_h
        x0, x1 = ox + left, ox + pw - right
        y0, y1 = oy + top, oy + ph - bottom - zero_gap  # log axis: y0 top (large error), y1 bottom
        yz = oy + ph - bottom  # the zero row

        def X(ms: float) -> float:
            return x0 + (math.log10(ms) - tx0) / (tx1 - tx0) * (x1 - x0)

        def Y(err: float) -> float:
            if err <= 0:
                return yz
            return y1 - (math.log10(err) - ey0) / (ey1 - ey0) * (y1 - y0)

        draw.text(
            ((x0 + x1) // 2, oy + top // 2),
            os.path.basename(shader.rstrip("/")) or shader,
            font=f_axis,
            fill=(0, 0, 0),
            anchor="mm",
        )
        # Grid, minor ticks and labels.
        for e in range(tx0, tx1 + 1):
            for m in range(1, 10):
                v = math.log10(m) + e
                if v > tx1:
                    break
                x = X(10**v)
                draw.line([(x, y0), (x, yz)], fill=GRID if m == 1 else (243, 243, 243), width=S)
            draw.text(
                (X(10**e), yz + 8 * S), _tick_text(e), font=f_tick, fill=(60, 60, 60), anchor="mt"
            )
        for e in range(ey0, ey1 + 1):
            for m in range(1, 10):
                v = math.log10(m) + e
                if v > ey1:
                    break
                y = Y(10**v)
                draw.line([(x0, y), (x1, y)], fill=GRID if m == 1 else (243, 243, 243), width=S)
            draw.text(
                (x0 - 6 * S, Y(10**e)), _tick_text(e), font=f_tick, fill=(60, 60, 60), anchor="rm"
            )
        draw.text((x0 - 6 * S, yz), "0", font=f_tick, fill=(60, 60, 60), anchor="rm")
        draw.line([(x0, yz), (x1, yz)], fill=GRID, width=S)
        # The axis break between the log range and the zero row.
        yb = (y1 + yz) / 2
        draw.rectangle([x0 - 3 * S, yb - 4 * S, x0 + 3 * S, yb + 4 * S], fill=(255, 255, 255))
        for d in (-3 * S, 3 * S):
            draw.line(
                [(x0 - 6 * S, yb + d + 2 * S), (x0 + 6 * S, yb + d - 2 * S)],
                fill=(0, 0, 0),
                width=S,
            )
        draw.line([(x0, y0), (x0, yz)], fill=(0, 0, 0), width=S)
        draw.line([(x0, yz), (x1, yz)], fill=(0, 0, 0), width=S)
        draw.text(
            ((x0 + x1) // 2, oy + ph - 18 * S),
            "median render time (ms, log scale)",
            font=f_axis,
            fill=(0, 0, 0),
            anchor="mm",
        )
        ylabel = Image.new("RGB", (int(y1 - y0 + zero_gap), 18 * S), (255, 255, 255))
        ImageDraw.Draw(ylabel).text(
            (ylabel.width // 2, ylabel.height // 2),
            "mean abs error vs reference (log)",
            font=f_axis,
            fill=(0, 0, 0),
            anchor="mm",
        )
        ylabel = ylabel.rotate(90, expand=True)
        img.paste(ylabel, (int(ox + 8 * S), int(y0)))

        # Pareto front: a staircase through the front points, fastest first.
        front = sorted((r for r in mine if r.pareto), key=lambda r: r.median_ms)
        pts = [(X(r.median_ms), Y(r.mean_abs_error)) for r in front]
        if pts:
            line = [pts[0]]
            for (xa, ya), (xb, yb_) in zip(pts, pts[1:]):
                line += [(xb, ya), (xb, yb_)]
            line.append((x1, line[-1][1]))
            line = [(pts[0][0], y0)] + line
            draw.line(line, fill=FRONT_COLOUR, width=3 * S, joint="curve")
            tag = (pts[0][0] + 5 * S, y0 + 4 * S)
            draw.text(tag, "Pareto front", font=f_label, fill=FRONT_COLOUR, anchor="lt")
            # Labels keep off the front line and its own label.
            taken = [
                (
                    min(a[0], b[0]) - 3 * S,
                    min(a[1], b[1]) - 3 * S,
                    max(a[0], b[0]) + 3 * S,
                    max(a[1], b[1]) + 3 * S,
                )
                for a, b in zip(line, line[1:])
            ]
            taken.append(
                (
                    tag[0],
                    tag[1],
                    tag[0] + draw.textlength("Pareto front", font=f_label),
                    tag[1] + 14 * S,
                )
            )
        else:
            taken = []
        taken.append((x0, yz - 2 * S, x1, yz + 2 * S))  # the zero row's axis line

        # Points, then labels placed where they overlap nothing drawn so far.
        r_mark = 6 * S
        placed = []
        for r in mine:
            x, y = X(r.median_ms), Y(r.mean_abs_error)
            if r.pareto:
                draw.ellipse(
                    [
                        x - r_mark - 4 * S,
                        y - r_mark - 4 * S,
                        x + r_mark + 4 * S,
                        y + r_mark + 4 * S,
                    ],
                    outline=FRONT_COLOUR,
                    width=2 * S,
                )
            _marker(draw, x, y, r.config.samples, _colour(r.config), r_mark)
            taken.append((x - r_mark, y - r_mark, x + r_mark, y + r_mark))
            placed.append((r, x, y))
        for r, x, y in sorted(placed, key=lambda p: (p[1], p[2])):
            text = r.config.label + (" (ref)" if r.config.is_reference else "")
            tw, th = draw.textbbox((0, 0), text, font=f_label)[2:]
            d = r_mark + (8 if r.pareto else 3) * S
            options = [
                (x + d, y - th / 2),
                (x - d - tw, y - th / 2),
                (x - tw / 2, y - d - th),
                (x - tw / 2, y + d),
                (x + d, y - th - 2 * S),
                (x + d, y + 2 * S),
                (x - d - tw, y - th - 2 * S),
                (x - d - tw, y + 2 * S),
            ]

            def overlap(box):
                return sum(
                    max(0, min(box[2], b[2]) - max(box[0], b[0]))
                    * max(0, min(box[3], b[3]) - max(box[1], b[1]))
                    for b in taken
                )

            def outside(box):
                return box[0] < x0 or box[2] > x1 or box[1] < y0 - 4 * S or box[3] > yz + 10 * S

            best = min(
                options,
                key=lambda o: (
                    outside((o[0], o[1], o[0] + tw, o[1] + th)),
                    overlap((o[0], o[1], o[0] + tw, o[1] + th)),
                ),
            )
            box = (best[0], best[1], best[0] + tw, best[1] + th)
            taken.append(box)
            draw.text(best[:2], text, font=f_label, fill=_colour(r.config))

    # Legend: colours are backends and precisions, shapes are samples per pixel.
    symbols: list[Callable[..., object]] = [
        lambda x, y, c=COLOURS[k]: draw.rectangle([x, y - 6 * S, x + 12 * S, y + 6 * S], fill=c)
        for k in colour_keys
    ]
    symbols += [
        lambda x, y, n=n: _marker(draw, x + 6 * S, y, n, (110, 110, 110), 6 * S) for n in (1, 4, 16)
    ]
    symbols.append(
        lambda x, y: draw.line([(x - 4 * S, y), (x + 14 * S, y)], fill=FRONT_COLOUR, width=3 * S)
    )
    for symbol, text, (x, row) in zip(symbols, texts, legend):
        y = title_h + ph + (11 + 22 * row) * S
        symbol(x, y)
        draw.text((x + 20 * S, y), text, font=f_axis, fill=(0, 0, 0), anchor="lm")

    img = img.resize((width // S, height // S), Image.Resampling.LANCZOS)
    from ..base.images import save_pil

    save_pil(img, path, "plot")  # atomic; InputError (exit 2) when it cannot be written
