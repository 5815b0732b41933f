"""Grading one submission: its tab files, the course's deductions, its renders, and how close
they are to the reference's.

    reference = render_reference("lab_shaders/07_final", options)
    grade = grade_submission(Submission("team-a", "repos/team-a", "lab4-main"), options, reference)

Each step that fails ends the submission's grading with the reason in `Grade.reason` (status
"failed") and keeps what the steps before found: a shader that does not compile still gets its
deductions (the linter reads code that does not compile) and its compile errors at
file:line:col; a render over the frame budget names the loop it was in. Nothing raises for a
bad submission; only a bad reference (the TA's input) raises.

Deductions are the linter's findings that cost points, with the course's default configuration:
a configuration file in the team's repository is not read and its `glslcheck: ignore` comments
do not silence a finding (they are listed in `Grade.suppressions` for the TA to weigh).
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass

import numpy as np

from ...backends import registry
from ...base.diagnostics import Diagnostic, GlslError, InputError, source_line
from ...base.images import png_bytes, quantise, thumbnail
from ...shadertoy.sources import Shader, load_shader
from ..compare import compare, diff_colours
from ..verify import compile_backend, engine_of
from . import closeness
from .records import CERTAIN, FAILED, POSSIBLE, Deduction, Frame, Grade, SourceError
from .submissions import Checkout, Submission, SubmissionError, submission_shader

DEFAULT_TIMES = (0.0, 1.7, 5.3)
DEFAULT_SIZE = (320, 180)


@dataclass(frozen=True)
class Options:
    """How a class is graded: render size and times, and the backend that renders."""

    size: tuple[int, int] = DEFAULT_SIZE
    times: tuple[float, ...] = DEFAULT_TIMES
    backend: str = registry.DEFAULT  # the default CPU program (backends/tiered.py)
    full_images: bool = False  # keep each render and diff as a full-size PNG (--images)


@dataclass
class Reference:
    """The reference solution's renders at the graded times, made once for the whole class."""

    name: str
    images: list[np.ndarray]
    thumbnails: list[bytes]
    animates: bool | None


def render_reference(path, options: Options) -> Reference:
    """Render the reference at every time; GlslError or InputError when it cannot (the TA's
    input is wrong: grading stops there)."""
    shader = load_shader(path)
    program = compile_backend(shader, options.backend)
    images = [program.render(size=options.size, time=t) for t in options.times]
    return Reference(
        str(path),
        images,
        [png_bytes(thumbnail(img)) for img in images],
        closeness.animates(images),
    )


def grade_submission(
    submission: Submission, options: Options, reference: Reference | None = None
) -> Grade:
    """Everything grade reports about one submission (see the module docstring)."""
    start = _time.perf_counter()
    grade = Grade(
        team=submission.team,
        source=submission.source,
        branch=submission.branch,
        contributors=list(submission.contributors),
    )
    try:
        with Checkout(submission) as checkout:
            _grade_checkout(grade, submission, checkout, options, reference)
    except SubmissionError as e:
        _fail(grade, str(e))
    except (InputError, GlslError) as e:  # anything the steps did not expect: still a row
        _fail(grade, _message(e))
    except RecursionError:
        _fail(grade, "the program is nested too deeply to analyse")
    except MemoryError:
        _fail(grade, "glslcheck ran out of memory on this shader")
    except Exception as e:  # noqa: BLE001 - a bug of glslcheck's must not stop the class
        _fail(grade, f"glslcheck could not grade it ({type(e).__name__}: {e}); please report it")
    grade.seconds = _time.perf_counter() - start
    return grade


def _fail(grade: Grade, reason: str) -> None:
    grade.status = FAILED
    grade.reason = reason


def _message(e: Exception) -> str:
    diagnostics = getattr(e, "diagnostics", None)
    if diagnostics:
        d = diagnostics[0]
        return f"{d.loc}: {d.message}" if d.loc else d.message
    return str(e).removeprefix("error: ")


def _grade_checkout(
    grade: Grade,
    submission: Submission,
    checkout: Checkout,
    options: Options,
    reference: Reference | None,
) -> None:
    shader = submission_shader(checkout.root, submission.path)
    where = checkout.relative
    grade.shader = where(shader.root) if shader.root else ""
    grade.tabs = [where(s.path) for s in shader.sources()]
    grade.deductions, grade.suppressions = _deductions(shader, where)
    try:
        program = compile_backend(shader, options.backend)
    except GlslError as e:
        grade.compiles = False
        grade.errors = [_source_error(d, where) for d in e.diagnostics if d.severity == "error"]
        first = grade.errors[0] if grade.errors else None
        _fail(grade, f"does not compile: {first}" if first else "does not compile")
        return
    grade.compiles = True
    images = []
    for i, t in enumerate(options.times):
        try:
            img = program.render(size=options.size, time=t)
        except GlslError as e:  # over the frame budget, a runaway loop: at its line
            grade.errors = [_source_error(d, where) for d in e.diagnostics]
            cause = grade.errors[0] if grade.errors else "the render failed"
            _fail(grade, f"render at iTime {t:g} failed: {cause}")
            return
        images.append(img)
        ref = reference.images[i] if reference else None
        grade.frames.append(_frame(img, t, ref, options.full_images))
        grade.frames[-1].engine = engine_of(program, options.backend)
    grade.animates = closeness.animates(images)
    _problems(grade, reference)
    if reference is not None:
        grade.verdict = closeness.worst([f.verdict for f in grade.frames if f.verdict])


def _frame(img: np.ndarray, t: float, ref: np.ndarray | None, full: bool) -> Frame:
    frame = Frame(
        time=float(t),
        nonfinite_pixels=closeness.nonfinite_pixels(img),
        flat=closeness.is_flat(img),
        thumbnail=png_bytes(thumbnail(img)),
        render=png_bytes(quantise(img[..., :3])) if full else b"",
    )
    if ref is not None:
        c = compare(img, ref)
        frame.verdict = closeness.verdict(c)
        frame.psnr_db = c.psnr_db
        frame.max_abs_error = c.max_abs_error
        frame.mean_abs_error = c.mean_abs_error
        pixels = c.size[0] * c.size[1]
        frame.over_tolerance = (c.mismatched_pixels + c.edge_pixels) / pixels if pixels else 0.0
        rgb = diff_colours(c)
        frame.diff = png_bytes(rgb) if full else b""
        frame.diff_thumbnail = png_bytes(thumbnail(rgb.astype(np.float32) / 255.0))
    return frame


def _problems(grade: Grade, reference: Reference | None) -> None:
    """What the renders show by themselves: NaN/Inf pixels, one flat colour, no animation."""
    nan = [f"{f.nonfinite_pixels} at iTime {f.time:g}" for f in grade.frames if f.nonfinite_pixels]
    if nan:
        grade.problems.append(
            f"NaN/Inf pixels: {', '.join(nan)} (glslcheck probe --nan finds where they come from)"
        )
    flat = [f.time for f in grade.frames if f.flat]
    if flat and len(flat) == len(grade.frames):
        grade.problems.append("the image is one flat colour at every time rendered")
    elif flat:
        grade.problems.append(
            "the image is one flat colour at iTime " + ", ".join(f"{t:g}" for t in flat)
        )
    if reference is not None and reference.animates and grade.animates is False:
        grade.problems.append("it does not animate (the reference does)")


def _source_error(d: Diagnostic, where) -> SourceError:
    if d.loc is None:
        return SourceError(d.message)
    return SourceError(
        d.message,
        where(d.loc.path),
        d.loc.line,
        d.loc.column,
        (source_line(d.loc.path, d.loc.line) or "").rstrip(),
    )


def certainty(finding) -> str:
    """ "possible" when the finding says the linter may be wrong here (a `certainty` of
    "possible", or `certain` False), else "certain": findings are read by their fields, so a
    linter without the distinction gives certain deductions."""
    if (
        getattr(finding, "certainty", None) == POSSIBLE
        or getattr(finding, "certain", True) is False
    ):
        return POSSIBLE
    return CERTAIN


def _deductions(shader: Shader, where) -> tuple[list[Deduction], list[str]]:
    """The findings that cost points, over every tab file, with the course's configuration
    (not the team's) and their `glslcheck: ignore` comments counted anyway."""
    from ...lint import LintConfig
    from ...lint.engine import lint_source, program_tree
    from ...lint.suppress import find_suppressions
    from ...lint.textscan import scan

    config = LintConfig()
    out: list[Deduction] = []
    silenced: list[str] = []
    for source in shader.sources():
        tree = program_tree(source, shader)
        findings = lint_source(
            source,
            config,
            shader,
            tree.ast,
            tree.model,
            errors=tree.errors,
            dropped=tree.dropped,
            honour_suppressions=False,
        )
        for f in findings:
            if f.penalty <= 0 or f.loc is None:
                continue
            out.append(
                Deduction(
                    rule=f.rule,
                    message=f.message,
                    file=where(f.loc.path),
                    line=f.loc.line,
                    column=f.loc.column,
                    penalty=int(f.penalty),
                    certainty=certainty(f),
                    code=(source_line(f.loc.path, f.loc.line) or "").rstrip(),
                )
            )
        for s in find_suppressions(source.path, scan(source.text).comments):
            silenced.append(f"{where(source.path)}:{s.line}: {s.text}")
    return out, silenced
