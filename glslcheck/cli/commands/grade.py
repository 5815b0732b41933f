"""glslcheck grade [SUBMISSION...] [--roster CSV] [--branch B] [--reference SHADER]
[--times T,...] [--size WxH] [--csv FILE] [--json FILE] [-o grades.html]: grade a class.

Each SUBMISSION is a folder of Shadertoy tab files, a tab file, or (with --branch) a git
repository: a local path or any URL git clones. A roster CSV (columns team, contributors, repo,
branch, optionally path) names the teams, their repositories and branches instead.

For every submission: the tab files found and whether they compile (errors at file:line:col);
every coding-standard deduction of the course's rubric (-1 each, with file:line; certain and
possible apart when the linter says so); renders at --times (a thumbnail each, NaN/Inf pixels,
a flat colour, no animation where the reference animates); against --reference, per-frame
error figures, a diff image and a verdict: same picture / close / different (thresholds:
docs/grading.md). A submission that cannot be graded (no such branch, no Image tab, it does not
compile, a render over --frame-budget, a binary file) gets its row with the reason; grading
goes on. Submissions are graded in parallel (--jobs), with a progress bar on a terminal.

Output: the table on standard output, `--csv`, `--json` (schema: docs/grading.md) and `-o` one
self-contained HTML page, sortable, that opens from disk. An existing output file is replaced
only when the new one is complete.

Exit 0 when every submission was graded, 1 when some could not be, 2 on usage or I/O errors or
a reference that does not render.
"""

from __future__ import annotations

import sys

from ...base import config, limits
from ...base.diagnostics import GlslError, InputError
from . import args as cli_args

# A frame of a lab part renders in well under a second at the graded size; a submission's
# frame still running after a minute is a runaway loop, and the class must not wait 300 s
# (render's default) for each of its frames.
GRADE_FRAME_SECONDS = 60.0


def _jobs(text: str) -> int:
    return limits.in_range(limits.whole_number(text, "--jobs"), 1, 256, "--jobs", text)


def add_arguments(p) -> None:
    p.add_argument(
        "paths", nargs="*", metavar="SUBMISSION", help="folders, tab files or git repositories"
    )
    p.add_argument(
        "--roster", metavar="CSV", help="teams, contributors, repositories and branches (CSV)"
    )
    p.add_argument(
        "--branch", metavar="NAME", help="the branch to grade in each SUBMISSION repository"
    )
    p.add_argument(
        "--path",
        metavar="FOLDER",
        help="the folder inside each submission that holds the tabs "
        "(when it holds several shaders)",
    )
    p.add_argument(
        "--reference", metavar="SHADER", help="the reference solution (a folder of tab files)"
    )
    p.add_argument(
        "--times",
        type=cli_args.arg(limits.parse_times),
        default=(0.0, 1.7, 5.3),
        metavar="T,...",
        help="iTime of each render (default 0,1.7,5.3)",
    )
    p.add_argument(
        "--size",
        type=cli_args.arg(limits.parse_size),
        default=(320, 180),
        metavar="WxH",
        help="render size (default 320x180)",
    )
    p.add_argument(
        "--backend",
        choices=("auto", "numpy", "compiled", "gl"),
        default="auto",
        help="what renders (default auto: the NumPy backend, then the compiled engine where "
        "that gives the same bits; the CPU engines honour --frame-budget)",
    )
    p.add_argument(
        "--jobs",
        type=cli_args.arg(_jobs),
        default=None,
        metavar="N",
        help="submissions graded at once (default: one per core)",
    )
    p.add_argument("--csv", metavar="FILE", help="write the grades as CSV")
    p.add_argument("--json", metavar="FILE", help="write everything as JSON")
    p.add_argument("-o", "--output", metavar="HTML", help="write the grades page")
    p.add_argument(
        "--images",
        metavar="FOLDER",
        help="write each render and diff image as PNG files there (named in the JSON)",
    )
    p.add_argument("--title", help="the page's title")


def run(args) -> int:
    from ...base.images import check_output
    from ...verification.grade import from_paths, read_roster

    for path, suffixes, what in (
        (args.output, (".html", ".htm"), "grades page (an HTML page)"),
        (args.csv, (".csv",), "CSV file"),
        (args.json, (".json",), "JSON file"),
    ):
        if path:
            check_output(path, suffixes, what)
    submissions = []
    if args.roster:
        submissions += read_roster(args.roster)
    if args.paths:
        submissions += from_paths(args.paths, args.branch)
    if not submissions:
        raise InputError("glslcheck grade: error: give SUBMISSION paths or --roster CSV")
    if args.path:
        for s in submissions:
            s.path = s.path or args.path
    seen: set[str] = set()
    for s in submissions:  # two teams of one name would share a row of the page and CSV
        if s.team in seen:
            raise InputError(f"glslcheck grade: error: two submissions are named {s.team!r}")
        seen.add(s.team)
    # --frame-budget (set by main), else the variable, else grade's own default; as it was after
    budget = None if args.frame_budget is not None else config.frame_seconds(GRADE_FRAME_SECONDS)
    with cli_args.environment(GLSLCHECK_FRAME_SECONDS=None if budget is None else repr(budget)):
        return _grade(args, submissions)


def _grade(args, submissions) -> int:
    from ...base.images import atomic_write
    from ...verification.grade import (
        GradeProgress,
        Options,
        grade_class,
        page_html,
        render_reference,
        to_csv,
        to_json,
        write_images,
    )
    from ...verification.grade.outputs import table

    options = Options(
        size=tuple(args.size),
        times=tuple(args.times),
        backend=args.backend,
        full_images=bool(args.images),
    )
    reference = None
    if args.reference:
        try:
            reference = render_reference(args.reference, options)
        except GlslError as e:
            d = e.diagnostics[0] if e.diagnostics else None
            raise InputError(
                f"{args.reference}: error: the reference does not render"
                + (f": {d.loc}: {d.message}" if d is not None and d.loc else "")
            ) from None
    progress = GradeProgress(len(submissions), enabled=sys.stderr.isatty())
    try:
        grades = grade_class(submissions, options, reference, jobs=args.jobs, progress=progress)
    finally:
        progress.finish()
    if args.images:
        write_images(grades, reference, args.images)
    ref_name = args.reference
    writes = []
    if args.csv:
        writes.append((args.csv, to_csv(grades), "CSV file"))
    if args.json:
        writes.append((args.json, to_json(grades, options, ref_name), "JSON file"))
    if args.output:
        title = args.title or "glslcheck grades" + (f" against {ref_name}" if ref_name else "")
        writes.append((args.output, page_html(grades, options, reference, title), "grades page"))
    for path, text, what in writes:
        with (
            atomic_write(path, what) as tmp,
            open(tmp, "w", encoding="utf-8", errors="backslashreplace") as f,
        ):
            f.write(text)
    sys.stdout.write(table(grades, ref_name))
    failed = [g.team for g in grades if g.status != "graded"]
    print(
        f"{len(grades)} submission{'s' * (len(grades) != 1)}, {len(grades) - len(failed)} graded"
        + (f", {len(failed)} could not be: {', '.join(failed)}" if failed else "")
        + "".join(f"; {path} written" for path, _, _ in writes),
        file=sys.stderr,
    )
    return 1 if failed else 0
