"""Code lines that no comment explains.

## What it does
Finds runs of code lines that no comment covers. A comment line covers the code lines right
below it, at most `comment-span` of them (3 by default), stopping at a blank line or the next
comment. A comment at the end of a code line covers that line; a comment before code on the same
line (`/* why */ x = 1.0;`, or code after a block comment's `*/`) covers that line and the
lines below it as a comment line would. Lines holding only braces (`{`, `}`, `};`, `} {`) need no
comment and use up none of a comment's span; a brace line with a comment (`{ // per light`) is a
comment line. Function, struct and struct-member lines and preprocessor lines (`#define`) are
code like any other. A `glslcheck:` directive is not an explanation and covers nothing.

One finding per run of consecutive uncovered code lines, at the run's first line.

Code in an `#ifdef`/`#if` branch the preprocessor skips is not compiled and is not linted
(where that is sure: `#ifdef`, `#ifndef`, `#if defined(X)`, `#if 0`). A comment that only
credits or marks ("Code from class by ...", "// part 3", "// TEST", a `-----` rule) says where
code came from, not why it is there: the lines only it covers are reported as advisory notes
(no points), apart from the deductions.

## Why is this bad?
The course's coding standards: "Every section, block and line of code must be commented
(-1 per ambiguous section/block/line). Clearly state the intent, the 'why' behind each section,
block and even line (or every few related lines) of code."

## Example
```glsl
float d = length(p - c);
float a = 1.0 / (1.0 + d / I + d * d / (I * I));
vec3 col = a * lightColor;
```

## Use instead
```glsl
// attenuate the light with distance (constant, linear and quadratic terms)
float d = length(p - c);
float a = 1.0 / (1.0 + d / I + d * d / (I * I));
vec3 col = a * lightColor; // the light reaching the surface
```
"""

from __future__ import annotations

import re

from ...base.diagnostics import Diagnostic
from ...base.regexes import compiled
from ..textscan import (
    BLANK,
    BRACE,
    BRACE_COMMENT,
    CODE,
    COMMENT,
    DIRECTIVE,
    LEADING,
    TRAILING,
    LineKind,
    inactive_lines,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ..engine import LintContext

NAME = "missing-comment"
PENALTY = 1
SEVERITY = "warning"
NEEDS = "text"

HELP = "add a comment above saying why these lines are there"


def uncovered_runs(kinds: list[LineKind], span: int) -> list[tuple[int, int, int]]:
    """(first line, last line, number of code lines) of each run of uncovered code lines."""
    runs: list[tuple[int, int, int]] = []
    budget = 0  # code lines the last comment line still covers
    run: list[int] | None = None  # [first, last, count]
    for number, kind in enumerate(kinds, start=1):  # the kinds as globals (see textscan)
        covered = True
        if kind is COMMENT or kind is BRACE_COMMENT:
            budget = span
        elif kind is BLANK:
            budget = 0
        elif kind is LEADING:
            budget = span - 1
        elif kind is CODE or kind is TRAILING:
            covered = kind is TRAILING or budget > 0
            budget = max(budget - 1, 0)
        # BRACE and DIRECTIVE lines neither need a comment nor use one up.
        if not covered:  # (only a CODE line is not: TRAILING and LEADING lines are covered)
            if run is None:
                run = [number, number, 0]
            run[1] = number
            run[2] += 1
        elif kind is not BRACE and kind is not DIRECTIVE and run is not None:
            runs.append((run[0], run[1], run[2]))
            run = None
    if run is not None:
        runs.append((run[0], run[1], run[2]))
    return runs


# A comment that only credits or marks ("code from class by ...", "// part 3", "// TEST"):
# it says where the code came from or where a part starts, not why the code is there.
ATTRIBUTION_RE = compiled(
    r"^[\s*/!-]*(?:"
    r"(?:code\s+|taken\s+|copied\s+|adapted\s+|borrowed\s+)?from\s+(?:class|the\s+starter|lecture)\b[^.;]*"
    # "Code by Dan Buckstein"
    r"|(?:\w+\s+){0,3}by\s+(?-i:[A-Z][\w.]*)(?:\s+(?-i:[A-Z][\w.]*)){0,3}"
    r"|(?:part|step|section)\s*[#\d.]+|test|todo"  # a bare marker
    r"|-{3,}|={3,}|\*{3,})[\s*/!.:-]*$",
    re.I,
)


def _attributions(ctx) -> set[int]:
    """Lines of whole-line comments that only attribute or mark."""
    return {
        c.line
        for c in ctx.comments
        if c.line == c.end_line
        and ctx.line_kinds[c.line - 1] is COMMENT
        and ATTRIBUTION_RE.match(c.text)
    }


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    # code the preprocessor skips (an inactive #ifdef branch) is not compiled: not linted
    inactive = inactive_lines(ctx.lines)
    kinds = (
        [DIRECTIVE if n in inactive else k for n, k in enumerate(ctx.line_kinds, start=1)]
        if inactive
        else ctx.line_kinds
    )
    span = ctx.config.comment_span
    runs = uncovered_runs(kinds, span)
    for first, last, count in runs:
        yield _finding(ctx, first, last, count, False, "without a comment")
    # lines that only an attribution or a marker "explains": advisory, not a deduction
    marks = _attributions(ctx)
    if marks:
        plain = [BLANK if n in marks else k for n, k in enumerate(kinds, start=1)]
        seen = {line for first, last, _ in runs for line in range(first, last + 1)}
        for first, last, count in uncovered_runs(plain, span):
            if not any(line in seen for line in range(first, last + 1)):
                yield _finding(
                    ctx,
                    first,
                    last,
                    count,
                    True,
                    "explained only by a comment that credits or marks (not why the code is there)",
                )


def _finding(
    ctx: LintContext, first: int, last: int, count: int, advisory: bool, what: str
) -> Diagnostic:
    lines = f"line {first}" if first == last else f"lines {first}-{last}"
    noun = "line" if count == 1 else "lines"
    return Diagnostic(
        f"{count} {noun} of code {what} ({lines})",
        ctx.location(first),
        severity="note" if advisory else SEVERITY,  # a note: advice, not a deduction
        help=HELP,
    )
