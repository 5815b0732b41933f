"""Fixes: a rule's rewrite of the source text that removes its finding, as data.

A rule that has a mechanical rewrite offers it on its finding (`Fixable.fix`): a `Fix` is a
title, the edits (spans of the linted file, in its `\\n` text, 1-based lines and columns as
every `Location`; end exclusive) and an applicability given before any proof:

    safe      the rewrite computes the same values (up to float rounding): `x * x` for
              `pow(x, 2.0)`, a local for a value computed twice, a uniform passed as a parameter
    unsafe    the rewrite holds only under a condition the rule cannot prove (a comparison's
              bound may be negative), or it needs the student's own text (a header template)

Whether a fix kept the picture is decided by rendering, in the verification layer
(`glslcheck.verification.fix_proof`), which the CLI wires to the linter: the lint layer only
offers, applies edits to text and writes files (`files.py`). Comments are never written for the
student; a fix that adds a line leaves its explanation to them.

Modules: `edits` (applying edits to a text), `build` (what rules use to make their edits:
source spans, parentheses, a local before a statement, fresh names), `uniforms` (a uniform
passed down every call chain from mainImage), `header` (the header template), `files` (read,
diff and write shader files keeping their line endings).
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...base.records import record

APPLICABILITIES = ("safe", "unsafe")


@record(frozen=True)
class Edit:
    """Replace the text from (line, column) to (end_line, end_column) with `text`. `item`: an
    item inserted into an empty comma list (`f()` -> `f(time)`); two such items at one place are
    joined with ", " (two uniforms passed to one function)."""

    line: int
    column: int
    end_line: int
    end_column: int
    text: str
    item: bool = False

    @property
    def start(self) -> tuple[int, int]:
        return (self.line, self.column)

    @property
    def end(self) -> tuple[int, int]:
        return (self.end_line, self.end_column)


@record(frozen=True)
class Fix:
    """One finding's rewrite: what it does (`title`), its edits in the file `path`, and its
    applicability before proof (`why` says what makes an unsafe one unsure)."""

    title: str
    path: str
    edits: tuple[Edit, ...]
    applicability: str = "safe"
    why: str = ""

    def overlaps(self, other: Fix) -> bool:
        """Whether two fixes touch the same text (an identical edit is shared, not a clash)."""
        mine = set(self.edits)
        for a in self.edits:
            for b in other.edits:
                if a == b and a in mine:
                    continue
                if _touch(a, b):
                    return True
        return False


def _touch(a: Edit, b: Edit) -> bool:
    """Whether two edits change the same text: overlapping spans, or an insertion strictly
    inside the other's span (insertions at one place, or at a span's end, keep both)."""
    if a.start == a.end and b.start == b.end:
        return False
    if a.start == a.end:
        return b.start < a.start < b.end
    if b.start == b.end:
        return a.start < b.start < a.end
    return a.start < b.end and b.start < a.end


@record
class Fixable(Diagnostic):
    """A rule's finding with the fix it offers (the engine copies `fix` onto the Finding)."""

    fix: Fix | None = None


__all__ = ["APPLICABILITIES", "Edit", "Fix", "Fixable"]
