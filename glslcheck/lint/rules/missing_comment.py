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

from typing import Iterator

from ...diagnostics import Diagnostic
from ..textscan import LineKind

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
    for number, kind in enumerate(kinds, start=1):
        covered = True
        if kind in (LineKind.COMMENT, LineKind.BRACE_COMMENT):
            budget = span
        elif kind is LineKind.BLANK:
            budget = 0
        elif kind is LineKind.LEADING:
            budget = span - 1
        elif kind in (LineKind.CODE, LineKind.TRAILING):
            covered = kind is LineKind.TRAILING or budget > 0
            budget = max(budget - 1, 0)
        # BRACE and DIRECTIVE lines neither need a comment nor use one up.
        if kind.has_code and not covered:
            if run is None:
                run = [number, number, 0]
            run[1] = number
            run[2] += 1
        elif kind not in (LineKind.BRACE, LineKind.DIRECTIVE) and run is not None:
            runs.append((run[0], run[1], run[2]))
            run = None
    if run is not None:
        runs.append((run[0], run[1], run[2]))
    return runs


def check(ctx) -> Iterator[Diagnostic]:
    for first, last, count in uncovered_runs(ctx.line_kinds, ctx.config.comment_span):
        lines = f"line {first}" if first == last else f"lines {first}-{last}"
        noun = "line" if count == 1 else "lines"
        yield Diagnostic(
            f"{count} {noun} of code without a comment ({lines})",
            ctx.location(first),
            rule=NAME,
            severity=SEVERITY,
            help=HELP,
        )
