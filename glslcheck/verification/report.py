"""One self-contained HTML page about shaders: source and findings, renders, differences, verdicts.

This module owns `glslcheck report`: for each shader (a tab file or a folder of tabs; several
shaders get an index at the top) the page shows

- the check (our checker and, where the browser runs, ANGLE's verdict) and the lint findings,
  each under the source line it is about, in the user's own tab files;
- the render of every backend side by side (the default CPU program: the NumPy backend, whose
  frames move to the compiled engine where that gives the same bits, backends/tiered.py; GL =
  Mesa llvmpipe, WebGL = ANGLE on SwiftShader in headless Chromium) with the time each render
  took and the engine that rendered it; the CPU side is named after that engine ("numpy");
- for each pair of backends the heat map of their differences (glslcheck.verification.compare's
  colours: black equal, red to white larger, cyan a discontinuity, magenta NaN in one image only)
  with verify's numbers and verdict; NumPy against WebGL is the driver-aware verdict of
  `verify --against webgl` (glslcheck/verification/drivers.py);
- where a render has NaN or Inf pixels, where they came from: `probe --nan`'s origins
  (glslcheck/verification/probe.py), each also under its source line, and a map of those pixels;
- the accuracy/time table and plot of `glslcheck bench` (glslcheck/verification/bench.py: each
  backend, NumPy at float16/32/64, 1, 4 and 16 samples per pixel, time against error), measured at a
  small size (BENCH_SIZE, 64x36: the twelve to fifteen configurations, float16 at 16 samples the
  slowest, then take seconds, not minutes, per shader) and said so on the page.

No network at view time: the CSS is inline and every image is a PNG data URI. A backend that is
not available here (no GL context, no browser) is named with the reason, the rest of the page
is still written. `load_in_browser` opens a written page in the headless Chromium of the WebGL
backend and returns its console errors (and takes a screenshot), which is how the page is tested.

Library API:

    page = build_report(["lab_shaders"], size=(320, 180), time=1.7, bench=(64, 36), bench_runs=3)
    page.html; page.ok   # ok: every shader clean, rendered and matching
    errors = load_in_browser("report.html", screenshot="report.png")
"""

from __future__ import annotations

import base64
import html
import io
import itertools
import math
import os
import tempfile
import time as _time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..backends import registry
from ..base.diagnostics import Diagnostic, GlslError, InputError, Location
from ..shadertoy.sources import Shader, find_shaders
from .bench import HEADER as BENCH_HEADER
from .bench import TABLE_NOTE, Row, row_cells
from .compare import NAN_COLOUR, Comparison, compare, diff_colours

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .probe import NanReport

DEFAULT_BACKENDS = (
    registry.DEFAULT,
    "gl",
    "webgl",
)  # the side under test first; GL and WebGL are the drivers
DEFAULT_SIZE = (320, 180)
BENCH_SIZE = (
    64,
    36,
)  # the bench renders 12-15 configurations x (runs + 1) at this size: keep it small
BENCH_RUNS = 3  # bench's own default: the median of three rounds

CSS = """
body { font: 14px/1.45 system-ui, sans-serif; margin: 0 auto; max-width: 1200px; padding: 16px 24px;
       color: #1d232a; background: #fafbfc; }
h1 { font-size: 22px; margin: 8px 0 4px; } h2 { font-size: 19px; margin: 28px 0 6px;
     border-bottom: 2px solid #d8dee4; padding-bottom: 4px; } h3 { font-size: 15px; \
margin: 16px 0 6px; }
.meta { color: #57606a; }
.badge { display: inline-block; padding: 1px 8px; border-radius: 10px; font-size: 12px; \
font-weight: 600; }
.ok { background: #dafbe1; color: #116329; } .bad { background: #ffebe9; color: #a40e26; }
.warn { background: #fff8c5; color: #7d4e00; } .off { background: #eaeef2; color: #57606a; }
table { border-collapse: collapse; margin: 6px 0; } td, th { padding: 3px 10px; text-align: left;
     border-bottom: 1px solid #d8dee4; } th { background: #f0f3f6; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.images { display: flex; flex-wrap: wrap; gap: 14px; }
figure { margin: 0; } figcaption { font-size: 12px; color: #57606a; max-width: 330px; }
img.render { width: 320px; image-rendering: pixelated; border: 1px solid #d8dee4; \
background: #000; }
pre.src { background: #fff; border: 1px solid #d8dee4; padding: 6px 0; overflow-x: auto; \
font-size: 12.5px;
          line-height: 1.4; margin: 4px 0; }
pre.src span.ln { display: inline-block; width: 3.5em; color: #8c959f; text-align: right; \
padding-right: 10px;
                  user-select: none; }
pre.src .hit { background: #fff8c5; display: inline-block; min-width: 100%; }
pre.src .note { display: block; color: #a40e26; padding-left: calc(3.5em + 10px); \
white-space: pre-wrap; }
pre.src .note.lint { color: #7d4e00; }
pre.src .note.nan { color: #9c1f9c; }
ul.diags { margin: 4px 0; padding-left: 20px; } code { font-size: 12.5px; }
table.bench tr.front td { background: #fff3e0; } table.bench td { padding: 2px 8px; \
font-size: 12.5px; }
img.plot { max-width: 520px; border: 1px solid #d8dee4; background: #fff; }
.index td:first-child a { font-weight: 600; }
"""


@dataclass(eq=False)
class ShaderReport:
    """Everything the page shows about one shader."""

    name: str
    shader: Shader
    check: list[Diagnostic] = field(default_factory=list)
    lint: list[Diagnostic] = field(default_factory=list)
    renders: dict[str, np.ndarray] = field(default_factory=dict)
    times_ms: dict[str, float] = field(default_factory=dict)
    unavailable: dict[str, str] = field(default_factory=dict)  # backend -> why
    engines: dict[str, str] = field(default_factory=dict)  # backend -> the engine that rendered
    tested: str = registry.DEFAULT  # the side under test (the first backend): a CPU engine
    pairs: list[tuple[str, str, Comparison, str]] = field(
        default_factory=list
    )  # a, b, comparison, note
    angle: bool = False  # ANGLE's verdict is part of `check`
    nonfinite: dict[str, int] = field(
        default_factory=dict
    )  # backend -> NaN/Inf pixels of its render
    nan: NanReport | None = (
        None  # probe --nan on the NumPy render, when a render has NaN/Inf pixels
    )
    nan_note: str = ""  # why there are no origins to show
    bench: list[Row] = field(default_factory=list)  # glslcheck bench's rows
    bench_note: str = ""  # why there is no table
    bench_load: tuple[float, float, float] | None = None  # load average when the bench ran

    @property
    def errors(self) -> int:
        return sum(d.severity == "error" for d in self.check)

    @property
    def ok(self) -> bool:
        # GL against WebGL compares two real drivers: their differences inform, they do not fail.
        return (
            not self.errors
            and bool(self.renders)
            and all(c.match for a, _, c, _ in self.pairs if a == self.tested)
        )


@dataclass(eq=False)
class Page:
    html: str
    shaders: list[ShaderReport]

    @property
    def ok(self) -> bool:
        return all(s.ok for s in self.shaders)


# ---------------------------------------------------------------------------------------------
# Gathering.


def _check(shader: Shader, webgl: bool) -> list[Diagnostic]:
    """Our checker over every program Shadertoy builds, then ANGLE's verdict (duplicates once)."""
    from ..frontend.parser import parse_shader
    from ..semantics import check
    from ..semantics.agreement import passes

    out: list[Diagnostic] = []
    for tab in passes(shader):
        try:
            out += check(parse_shader(shader, tab), tab, collect=True).diagnostics
        except GlslError as e:
            out += e.diagnostics
        if webgl:
            from ..backends.webgl import webgl_diagnostics

            out += webgl_diagnostics(shader, tab)
    seen, unique = set(), []
    for d in out:
        key = (str(d.loc), d.message, d.severity)
        if key not in seen:
            seen.add(key)
            unique.append(d)
    return unique


def _lint(shader: Shader) -> list[Diagnostic]:
    from ..lint import lint_paths

    try:
        return list(lint_paths([s.path for s in shader.sources()]).findings)
    except InputError as e:  # a bad configuration: shown, not fatal
        return [Diagnostic(str(e), None, rule="lint")]


def _backend_ready(backend: str) -> str | None:
    """None when `backend` can run here, else why not (the environment, not the shader)."""
    try:
        registry.get(backend).check_ready()
    except InputError as e:
        return str(e).removeprefix("error: ")
    return None


def _nan_origins(report: ShaderReport, size, time: float) -> None:
    """`probe --nan` when a render has NaN/Inf pixels: the probe traces the NumPy backend's
    module, so it finds the origins of NumPy's own NaN pixels (the others are counted)."""
    for b, image in report.renders.items():
        report.nonfinite[b] = int((~np.isfinite(image)).any(axis=-1).sum())
    if not any(report.nonfinite.values()):
        return
    from .probe import Inputs, Probe

    try:
        report.nan = Probe(report.shader).nan_origins(Inputs(size=tuple(size), time=float(time)))
    except (
        GlslError,
        InputError,
    ) as e:  # e.g. buffers and channels, which the probe does not trace
        report.nan_note = str(e).removeprefix("error: ")


def _bench(report: ShaderReport, size, runs: int, time: float) -> None:
    """`glslcheck bench`'s table for one shader, WebGL included when the page shows it."""
    from .bench import bench_shader

    if "gl" in report.unavailable:  # the bench's times are ratios to GL at one sample
        report.bench_note = f"not measured: GL is not available ({report.unavailable['gl']})"
        return
    report.bench_load = os.getloadavg() if hasattr(os, "getloadavg") else None
    try:
        report.bench = bench_shader(
            report.shader,
            size=tuple(size),
            runs=runs,
            time=float(time),
            webgl="webgl" in report.renders,
        )
    except (
        GlslError,
        InputError,
    ) as e:  # a render only the bench makes fails (float16, 16 samples)
        said = "; ".join(
            f"{d.loc}: {d.message}" if d.loc else d.message for d in getattr(e, "diagnostics", [])
        )
        report.bench_note = "not measured: " + (said or str(e).removeprefix("error: "))


def gather(
    shader: Shader,
    *,
    size=DEFAULT_SIZE,
    time: float = 0.0,
    backends=DEFAULT_BACKENDS,
    ready: dict[str, str | None] | None = None,
    bench=BENCH_SIZE,
    bench_runs: int = BENCH_RUNS,
) -> ShaderReport:
    """Check, lint, render with each backend and compare every pair, for one shader; then the
    NaN origins (when a render has NaN/Inf pixels) and, unless `bench` is None, the bench at
    that size."""
    from .drivers import driver_verdict
    from .verify import FrameSpec, UndefinedSide, _Pair, compile_backend, emulate_driver, engine_of

    ready = ready if ready is not None else {b: _backend_ready(b) for b in backends}
    name = shader.root or (shader.image.path if shader.image else "<shader>")
    report = ShaderReport(name, shader, tested=backends[0] if backends else registry.DEFAULT)
    report.unavailable = {b: why for b, why in ready.items() if why}
    report.angle = "webgl" in backends and "webgl" not in report.unavailable
    report.check = _check(shader, report.angle)
    report.lint = _lint(shader)
    if report.errors:
        return report
    usable = [b for b in backends if b not in report.unavailable]
    programs = {}
    for b in usable:
        try:
            programs[b] = compile_backend(shader, b)
        except GlslError as e:  # e.g. only the driver rejects it: shown with the check
            report.check += [d for d in e.diagnostics if d not in report.check]
    emulate_driver(list(programs.values()))
    spec = FrameSpec(time=float(time))
    for b, program in programs.items():
        start = _time.perf_counter()
        try:
            (image,) = _Pair([program]).render(
                spec, tuple(size), (0.0, 0.0, 0.0, 0.0), None, "float32", 1
            )
        except GlslError as e:  # a runaway loop, a lost context: shown, the rest goes on
            report.check += e.diagnostics
            continue
        report.times_ms[b] = (_time.perf_counter() - start) * 1000.0
        report.renders[b] = image
        report.engines[b] = engine_of(program, b)
    r = report.renders
    for a, b in itertools.combinations([x for x in backends if x in r], 2):
        if (a, b) == (report.tested, "webgl") and "gl" in r:
            verdict, plain, drivers = driver_verdict(r[a], r[b], r["gl"])
            n = int(drivers.mismatched_pixels + drivers.edge_pixels)
            note = (
                (
                    f"{n} driver-dependent pixels (GL and WebGL differ): "
                    "there NumPy need match only the closer "
                    f"driver; NumPy against WebGL alone: {plain.mismatched_pixels} mismatched, "
                    f"{plain.edge_pixels} edge"
                )
                if n
                else ""
            )
            report.pairs.append((a, b, verdict, note))
        else:
            c = compare(r[a], r[b])
            if not c.match and a == report.tested:
                # pixels that depend on the shader's undefined reads (verify.UndefinedSide)
                pair = _Pair([programs[a], programs[b]])
                side = UndefinedSide(shader, pair.programs, numpy_under_test=True)
                inputs = pair.inputs(spec, tuple(size), (0.0, 0.0, 0.0, 0.0), None, "float32", 1)
                undefined = side.mask(inputs, r[a])
                if undefined is not None:
                    c = compare(r[a], r[b], undefined=undefined)
                    # compare sets the mask of the pixels it counts
                    if c.undefined_pixels and c.undefined_mask is not None:
                        c.undefined_lines = side.lines(inputs, c.undefined_mask)
            report.pairs.append((a, b, c, ""))
    _nan_origins(report, size, time)
    if bench is not None and r:
        _bench(report, bench, bench_runs, time)
    return report


# ---------------------------------------------------------------------------------------------
# HTML.


def _png(rgb: np.ndarray) -> str:
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(rgb).save(buf, format="PNG", optimize=True)
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def _screen(image: np.ndarray) -> np.ndarray:
    """RGB as the screen shows it: clamped to [0, 1], *255 + 0.5, NaN as 0 (as `render -o
    x.png`)."""
    with np.errstate(invalid="ignore"):
        q = np.floor(np.clip(np.nan_to_num(image[..., :3], nan=0.0), 0.0, 1.0) * 255.0 + 0.5)
    return q.astype(np.uint8)


def render_png(image: np.ndarray) -> str:
    """A render as the screen shows it."""
    return _png(_screen(image))


def nan_map_png(image: np.ndarray) -> str:
    """The render as the screen shows it, its NaN/Inf pixels in compare's NaN colour."""
    q = _screen(image)
    q[(~np.isfinite(image)).any(axis=-1)] = NAN_COLOUR
    return _png(q)


def plot_png(rows: list[Row], title: str) -> str:
    """bench's time-against-error plot (bench.write_plot) as a data URI."""
    from .bench import write_plot

    with tempfile.TemporaryDirectory(prefix="glslcheck-report-") as folder:
        path = Path(folder) / "plot.png"
        write_plot(rows, path, title=title)
        return "data:image/png;base64," + base64.b64encode(path.read_bytes()).decode("ascii")


def diff_png(c: Comparison) -> str:
    """The heat map `verify --diff` writes."""
    return _png(diff_colours(c))


def escape(text) -> str:
    """Any value as HTML text or an attribute value (quotes escaped too)."""
    return html.escape(str(text), quote=True)


_e = escape


def _anchor(name: str) -> str:
    return "s-" + "".join(ch if ch.isalnum() else "-" for ch in name)


def _badge(ok: bool, yes: str = "match", no: str = "MISMATCH") -> str:
    return f'<span class="badge {"ok" if ok else "bad"}">{yes if ok else no}</span>'


def _pair_badge(c: Comparison) -> str:
    """The badge of the renderer under test against a driver."""
    if c.verdict == "undefined":
        return '<span class="badge warn">undefined in the shader</span>'
    return _badge(c.match)


def _num(v: float) -> str:
    return "inf" if math.isinf(v) else f"{v:.4g}"


def _source_html(shader: Shader, diags: list[Diagnostic]) -> str:
    """Each tab file with line numbers; every finding under its line (others listed after)."""
    parts = []
    placed: set[int] = set()
    for src in shader.sources():
        by_line: dict[int, list[Diagnostic]] = {}
        for i, d in enumerate(diags):
            if d.loc is not None and d.loc.path == src.path:
                by_line.setdefault(d.loc.line, []).append(d)
                placed.add(i)
        rows = []
        for number, line in enumerate(src.text.split("\n"), 1):
            if number == len(src.text.split("\n")) and not line:
                break
            text = f'<span class="ln">{number}</span>{_e(line)}'
            hits = by_line.get(number, [])
            # a note is a block of its own: no newline after it, or the listing gets blank lines
            rows.append(f'<span class="hit">{text}</span>' if hits else text + "\n")
            for d in hits:
                assert d.loc is not None  # (placed by its location)
                kind = (
                    "nan"
                    if d.rule == NAN_RULE
                    else "lint"
                    if d.rule not in ("type", "syntax", "webgl-compile", "gl-compile")
                    else "check"
                )
                rows.append(
                    f'<span class="note {kind}">{"^".rjust(d.loc.column)} {_e(d.severity)} '
                    f"[{_e(d.rule)}] {_e(d.message)}</span>"
                )
        parts.append(f'<h3>{_e(src.path)}</h3><pre class="src">' + "".join(rows) + "</pre>")
    rest = [d for i, d in enumerate(diags) if i not in placed]
    if rest:
        parts.append(
            '<ul class="diags">'
            + "".join(f"<li>{_e(d.severity)} [{_e(d.rule)}] {_e(d.message)}</li>" for d in rest)
            + "</ul>"
        )
    return "\n".join(parts)


NAN_RULE = "nan-origin"  # the probe's origins, shown under their source lines like findings


def _origin_notes(r: ShaderReport) -> list[Diagnostic]:
    if r.nan is None:
        return []
    return [
        Diagnostic(
            f"{o.operation} in `{o.code}`: the first NaN/Inf of {o.pixels} "
            f"pixel{'s' * (o.pixels != 1)}",
            # (the unknown origin has no location: None in each field, placed nowhere)
            Location(o.file, o.line, o.column),  # type: ignore[arg-type]
            severity="note",
            rule=NAN_RULE,
        )
        for o in r.nan.origins
        if o.file
    ]


def _nan_html(r: ShaderReport) -> str:
    """NaN/Inf pixels per render and, from `probe --nan`, where NumPy's came from."""
    if not any(r.nonfinite.values()):
        return ""
    counts = ", ".join(f"{registry.get(b).title} {n}" for b, n in r.nonfinite.items())
    out = [
        "<h3>NaN and Inf pixels: where they came from</h3>",
        f'<p class="meta">Pixels with a NaN or Inf channel per render: {_e(counts)}. '
        "The origins are "
        "<code>glslcheck probe --nan</code>'s (glslcheck/verification/probe.py): "
        "it runs the NumPy backend's traced module "
        "on each such pixel of the NumPy render and groups the pixels by the first operation "
        "that made a NaN or Inf. Each origin is also noted under its source line below.</p>",
    ]
    if r.nan is None:
        out.append(f'<p><span class="badge off">no origins</span> {_e(r.nan_note)}</p>')
        return "\n".join(out)
    rows = []
    for o in r.nan.origins:
        where = f"{o.file}:{o.line}:{o.column}" if o.file else "-"
        x0, y0, x1, y1 = o.box
        rows.append(
            f"<tr><td><code>{_e(where)}</code></td><td>{_e(o.operation)}</td><td><code>{_e(o.code)}</code></td>"
            f'<td class="num">{o.pixels}</td><td class="num">{x0},{y0} .. {x1},{y1}</td>'
            f"<td>{_e(o.help)}</td></tr>"
        )
    if not rows:
        rows.append(
            '<tr><td colspan="6">the NumPy render has no NaN or Inf pixel: '
            "only the drivers made them</td></tr>"
        )
    figure = ""
    cpu = r.tested
    if cpu in r.renders and r.nonfinite.get(cpu):
        figure = (
            f'<figure><img class="render" alt="NaN/Inf pixels of the NumPy render" '
            f'src="{nan_map_png(r.renders[cpu])}"><figcaption>NumPy render, '
            "NaN/Inf pixels in magenta"
            "</figcaption></figure>"
        )
    out.append(
        f'<div class="images">{figure}<table '
        'class="nan"><tr><th>where</th><th>operation</th><th>code</th>'
        "<th>pixels</th><th>box (x, y from the top "
        f"left)</th><th>help</th></tr>{''.join(rows)}</table></div>"
    )
    return "\n".join(out)


def _bench_html(r: ShaderReport, runs: int, size, time: float) -> str:
    """bench's table and plot, with what was measured and how."""
    out = ["<h3>Accuracy against time (glslcheck bench)</h3>"]
    if not r.bench:
        if r.bench_note:
            out.append(f'<p><span class="badge off">no table</span> {_e(r.bench_note)}</p>')
        return "\n".join(out) if r.bench_note else ""
    w, h = size
    load = (
        (
            f" Load average when measured: {r.bench_load[0]:.2f}, {r.bench_load[1]:.2f}, "
            f"{r.bench_load[2]:.2f} "
            f"on {os.cpu_count()} CPUs: times on a busy machine are slower and noisier; "
            "compare rows, which share the load (round-robin), rather than absolute times."
        )
        if r.bench_load
        else ""
    )
    out.append(
        f'<p class="meta">Measured as <code>glslcheck bench --size {w}x{h} --runs {runs} --time '
        f"{time:g}"
        f"{' --webgl' if any(x.config.backend == 'webgl' for x in r.bench) else ''}</code> does "
        "(glslcheck/verification/bench.py), at this small size to keep the report quick. "
        "Each configuration (backend, "
        "precision, samples per pixel on a 1x1, 2x2 or 4x4 sub-pixel grid) renders once to warm "
        "up, then "
        f"{runs} round{'s' * (runs != 1)} in turn; its time is the median of its rounds of the "
        "whole render call (uniforms, "
        "every sample, the averaging, the image back in memory). Error: RGB as the screen shows it "
        "(clamped to [0, 1]) against NumPy float64 at 16 samples per pixel, "
        "with verification/compare.py's metrics; "
        f"px &gt; 1/255: pixels off by more than one 8-bit step.{_e(load)}</p>"
    )
    head = "".join(f"<th>{_e(c)}</th>" for c in BENCH_HEADER)
    rows = []
    for x in r.bench:
        cells = row_cells(x)
        tds = "".join(
            f"<td>{_e(c)}</td>" if i < 3 else f'<td class="num">{_e(c)}</td>'
            for i, c in enumerate(cells)
        )
        rows.append(('<tr class="front">' if x.pareto else "<tr>") + tds + "</tr>")
    title = f"render time against error at {w}x{h} (reference: NumPy float64 at 16 samples)"
    out.append(
        f'<div class="images"><table class="bench"><tr>{head}</tr>{"".join(rows)}</table>'
        f'<img class="plot" alt="render time against error" src="{plot_png(r.bench, title)}"></div>'
    )
    out.append(f'<p class="meta">{_e(TABLE_NOTE)} (shaded rows).</p>')
    return "\n".join(out)


def _label(r: ShaderReport, backend: str) -> str:
    """How the page names a side: the default CPU program after the engine that rendered it
    ("numpy", "compiled"), as verify's text does; any other backend by its name."""
    if backend != registry.DEFAULT:
        return backend
    return r.engines.get(backend, "numpy").split()[0]


def _pair_table(a: str, b: str, c: Comparison) -> str:
    rows = [
        ("max abs error", _num(c.max_abs_error)),
        ("mean abs error", f"{c.mean_abs_error:.3g}"),
        ("PSNR", "inf" if math.isinf(c.psnr_db) else f"{c.psnr_db:.1f} dB"),
        ("mismatched pixels", f"{c.mismatched_pixels} (budget {int(c.mismatch_budget)})"),
        ("edge pixels", f"{c.edge_pixels} (budget {int(c.edge_budget)})"),
        ("NaN/Inf pixels", f"{a} {c.nan_numpy}, {b} {c.nan_gl}"),
    ]
    if c.undefined_pixels:
        rows.append(("undefined pixels", f"{c.undefined_pixels} (not counted)"))
        rows += [
            (f"undefined read, line {u['line']}", f"{u['kind']}: {u['pixels']} pixels")
            for u in c.undefined_lines[:3]
        ]
    return (
        "<table>"
        + "".join(f'<tr><td>{k}</td><td class="num">{_e(v)}</td></tr>' for k, v in rows)
        + "</table>"
    )


def _section(
    r: ShaderReport, size, time: float, bench_size=BENCH_SIZE, bench_runs: int = BENCH_RUNS
) -> str:
    out = [f'<h2 id="{_anchor(r.name)}">{_e(r.name)} {_badge(r.ok, "ok", "problems")}</h2>']
    errors = r.errors
    warnings = sum(d.severity == "warning" for d in r.check)
    check_state = (
        "" if not errors else f'<span class="badge bad">{errors} error{"s" * (errors != 1)}</span> '
    )
    lint_state = (
        f'<span class="badge warn">{len(r.lint)} lint finding{"s" * (len(r.lint) != 1)}</span>'
        if r.lint
        else '<span class="badge ok">no lint findings</span>'
    )
    out.append(
        f"<p>{check_state or _badge(True, 'checks clean')} {lint_state} "
        f'<span class="meta">check: glslcheck{" + ANGLE" if r.angle else ""}; '
        f"{warnings} warning{'s' * (warnings != 1)}</span></p>"
    )
    out.append("<h3>Renders</h3>")
    w, h = size
    out.append(
        f'<p class="meta">{w}x{h}, iTime {time:g}, iFrame 0, one sample per pixel; '
        "RGB as the screen shows it (clamped, 8-bit)</p>"
    )
    figs = []
    for b in (b for b in registry.names() if b in r.renders or b in r.unavailable):
        name = registry.get(b).title
        if b in r.renders:
            by = r.engines.get(b, b)
            engine = f", by {'the NumPy backend' if by == 'numpy' else by}" if by != b else ""
            figs.append(
                f'<figure><img class="render" alt="{_e(name)} render" '
                f'src="{render_png(r.renders[b])}">'
                f"<figcaption><b>{_e(name)}</b> {r.times_ms[b]:.0f} ms{_e(engine)}</figcaption>"
                "</figure>"
            )
        elif b in r.unavailable:
            figs.append(
                f'<figure><span class="badge off">{_e(name)}: not available</span>'
                f"<figcaption>{_e(r.unavailable[b])}</figcaption></figure>"
            )
    if errors:
        figs.append(
            '<p><span class="badge bad">not rendered</span> the shader has errors (see below)</p>'
        )
    out.append('<div class="images">' + "".join(figs) + "</div>")
    if r.pairs:
        out.append("<h3>Differences</h3>")
        figs = []
        for a, b, c, note in r.pairs:
            badge = (
                _pair_badge(c)
                if a == r.tested
                else (
                    '<span class="badge ok">drivers agree</span>'
                    if c.match
                    else '<span class="badge warn">drivers differ</span>'
                )
            )
            la, lb = _label(r, a), _label(r, b)
            caption = f"<b>{_e(la)} vs {_e(lb)}</b> {badge}"
            figs.append(
                f'<figure><img class="render" alt="difference {_e(la)} vs {_e(lb)}" '
                f'src="{diff_png(c)}">'
                f"<figcaption>{caption}{_pair_table(la, lb, c)}{_e(note)}</figcaption></figure>"
            )
        out.append('<div class="images">' + "".join(figs) + "</div>")
        out.append(
            '<p class="meta">Heat map: black = equal, red to yellow to white = larger differences, '
            "cyan = a difference a sub-pixel shift explains (an edge), "
            "magenta = NaN/Inf in one image "
            "only. Tolerance and budgets: glslcheck/verification/compare.py.</p>"
        )
    out.append(_nan_html(r))
    out.append(_bench_html(r, bench_runs, bench_size, time))
    out.append("<h3>Source, check and lint findings</h3>")
    out.append(_source_html(r.shader, r.check + r.lint + _origin_notes(r)))
    return "\n".join(out)


def page_html(
    reports: list[ShaderReport],
    size,
    time: float,
    title: str,
    bench_size=BENCH_SIZE,
    bench_runs: int = BENCH_RUNS,
) -> str:
    from ..base.version import __version__

    head = (
        f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        f'<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>{_e(title)}</title><style>{CSS}</style></head><body>"
    )
    body = [
        f"<h1>{_e(title)}</h1>",
        f'<p class="meta">glslcheck {__version__} report: {len(reports)} '
        f"shader{'s' * (len(reports) != 1)}, "
        f"renders at {size[0]}x{size[1]}, iTime {time:g}</p>",
    ]
    if len(reports) > 1:
        rows = []
        for r in reports:
            verdicts = (
                " ".join(
                    f"{_label(r, a)}/{_label(r, b)} {_pair_badge(c)}"
                    for a, b, c, _ in r.pairs
                    if a == r.tested
                )
                or "-"
            )
            rows.append(
                f'<tr><td><a href="#{_anchor(r.name)}">{_e(Path(r.name).name or r.name)}</a></td>'
                f"<td>{_badge(not r.errors, 'clean', f'{r.errors} errors')}</td>"
                f'<td class="num">{len(r.lint)}</td><td>{verdicts}</td></tr>'
            )
        body.append(
            '<table class="index"><tr><th>shader</th><th>check</th><th>lint findings</th>'
            "<th>verify</th></tr>" + "".join(rows) + "</table>"
        )
    body += [_section(r, size, time, bench_size, bench_runs) for r in reports]
    return head + "\n".join(body) + "\n</body></html>\n"


def build_report(
    paths,
    *,
    size=DEFAULT_SIZE,
    time: float = 0.0,
    backends=DEFAULT_BACKENDS,
    title: str | None = None,
    bench=BENCH_SIZE,
    bench_runs: int = BENCH_RUNS,
) -> Page:
    """The page for every shader under `paths` (see the module docstring); `bench` is the
    bench's render size, None to leave the table out."""
    shaders = find_shaders([str(p) for p in paths])
    ready = {b: _backend_ready(b) for b in backends}
    reports = [
        gather(
            s,
            size=size,
            time=time,
            backends=backends,
            ready=ready,
            bench=bench,
            bench_runs=bench_runs,
        )
        for s in shaders
    ]
    title = title or ("glslcheck report: " + ", ".join(str(p) for p in paths))
    return Page(page_html(reports, size, time, title, bench, bench_runs), reports)


def load_in_browser(
    path, screenshot=None, width: int = 1280, height: int | None = None
) -> list[str]:
    """Open a written page in the WebGL backend's headless Chromium; its console errors, page
    errors and requests that left the page (there must be none: everything is inline).
    With `screenshot` a PNG of the page is written there: the whole page, or its top `height`
    pixels."""
    from ..backends.webgl import get_browser

    browser = get_browser()
    page = browser.new_page(viewport={"width": width, "height": 800})
    problems: list[str] = []
    page.on(
        "console",
        lambda m: problems.append(f"console {m.type}: {m.text}") if m.type == "error" else None,
    )
    page.on("pageerror", lambda e: problems.append(f"page error: {e}"))
    page.on(
        "request",
        lambda q: (
            None if q.url.startswith(("data:", "file:")) else problems.append(f"request: {q.url}")
        ),
    )
    try:
        page.goto(Path(path).resolve().as_uri())
        if screenshot is not None:
            clip = None if height is None else {"x": 0, "y": 0, "width": width, "height": height}
            page.screenshot(path=str(screenshot), full_page=True, clip=clip, timeout=300_000)
    finally:
        page.close()
    return problems
