"""Inline and file-wide suppressions: reading them from comments and applying them to findings.

    x = 1.0; // glslcheck: ignore[missing-comment]            findings of that rule starting on this
                                                              line
    // glslcheck: ignore[rule-a, rule-b]                        several rules (comma-separated)
    // glslcheck: ignore-file[missing-credit]                   that rule's findings anywhere in the
                                                                file

A suppression applies to a finding whose location starts on the suppression's line (rules report
the narrowest span, so its start line is where a suppression goes). Each suppression remembers
which of its names silenced something; the `unused-suppression` rule reports the rest, and any
directive it cannot read.
"""

from __future__ import annotations

from ..base.diagnostics import Diagnostic, Location
from ..base.records import field, record
from .textscan import DIRECTIVE_RE, Comment

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterable

VERBS = {"ignore": False, "ignore-file": True}  # verb -> applies to the whole file


@record
class Suppression:
    """One `glslcheck:` directive in a comment. `names` empty and `problem` set when unreadable."""

    names: tuple[str, ...]
    file_wide: bool
    loc: Location  # the directive's own span (`glslcheck: ignore[...]`)
    text: str
    problem: str | None = None
    used: set[str] = field(default_factory=set)

    @property
    def line(self) -> int:
        return self.loc.line


def _position(comment: Comment, offset: int) -> tuple[int, int]:
    """Line and column in the file of character `offset` of a comment's text."""
    before = comment.text[:offset]
    newlines = before.count("\n")
    if newlines == 0:
        return comment.line, comment.column + 2 + offset
    return comment.line + newlines, len(before) - before.rfind("\n")


def find_suppressions(path: str, comments: Iterable[Comment]) -> list[Suppression]:
    """Every `glslcheck:` directive in the comments, readable or not."""
    out: list[Suppression] = []
    for c in comments:
        for m in DIRECTIVE_RE.finditer(c.text):
            line, col = _position(c, m.start())
            end_line, end_col = _position(c, m.end())
            loc = Location(path, line, col, end_line, end_col)
            verb, names = m.group("verb"), m.group("names")
            if verb not in VERBS:
                out.append(
                    Suppression((), False, loc, m.group(0), problem=f"unknown directive `{verb}`")
                )
                continue
            parsed = tuple(n.strip() for n in (names or "").split(",") if n.strip())
            if not parsed:
                problem = (
                    f"`{verb}` needs rule names in brackets, e.g. `glslcheck: "
                    f"{verb}[missing-comment]`"
                )
                out.append(Suppression((), VERBS[verb], loc, m.group(0), problem=problem))
                continue
            out.append(Suppression(parsed, VERBS[verb], loc, m.group(0)))
    return out


def is_suppressed(d: Diagnostic, suppressions: Iterable[Suppression]) -> bool:
    """Whether a suppression silences `d`; marks every suppression that does as used."""
    hit = False
    line = d.loc.line if d.loc is not None else None
    for s in suppressions:
        if d.rule in s.names and (s.file_wide or s.line == line):
            s.used.add(d.rule)
            hit = True
    return hit
