"""One unit (a Shadertoy tab or GLSL file) after the first phases of preprocessing:
backslash-newlines spliced, comments collected and replaced, and the map from offsets of the
stripped text back to the user's lines and columns.
"""

from __future__ import annotations

from bisect import bisect_right

from ...base.diagnostics import Diagnostic, GlslError, Location, pending_location
from ...base.records import record
from ...base.regexes import compiled
from ...shadertoy.sources import Source

RULE = "preprocessor"  # the rule of every diagnostic the preprocessor makes
_COMMENT_RE = compiled(r"//|/\*")
_NEWLINE_RE = compiled("\n")


@record
class Comment:
    """One comment of the user's text, as written (`//...` or `/*...*/`)."""

    loc: Location  # the span of the whole comment
    text: str
    kind: str  # "line" | "block"
    active: bool = True  # False inside an #if group that is skipped


class Unit:
    """A source file after phases 1-2: `stripped` is its text with backslash-newlines removed
    and comments replaced; `point`/`span` map stripped offsets to the user's lines/columns."""

    def __init__(self, src: Source, index: int):
        self.path = src.path
        self.index = index
        raw = src.text
        self.raw = raw
        self.line_starts = [0] + [m.end() for m in _NEWLINE_RE.finditer(raw)]
        # Phase 1: splice lines. clean offset c maps to raw c + 2 * (splices at clean offsets <= c).
        if "\\\n" in raw:
            pieces = raw.split("\\\n")
            self.splices, acc = [], 0
            for p in pieces[:-1]:
                acc += len(p)
                self.splices.append(acc)
            clean = "".join(pieces)
        else:
            self.splices, clean = [], raw
        # Phase 2: comments. Breakpoints (stripped offset, raw offset) of a piecewise-linear map.
        self.bp_s: list[int] = []
        self.bp_r: list[int] = []
        self.soft_newlines: set[int] = set()  # newlines standing for a multi-line comment
        self.comments: list[Comment] = []
        self.comment_starts: list[int] = []
        out: list[str] = []
        olen = 0
        pos = 0
        n = len(clean)
        while True:
            m = _COMMENT_RE.search(clean, pos)
            cstart = m.start() if m else n
            if cstart > pos:
                self._add_piece(olen, pos, cstart)
                out.append(clean[pos:cstart])
                olen += cstart - pos
            if m is None:
                break
            if m.group() == "//":
                cend = clean.find("\n", cstart)
                cend = n if cend < 0 else cend
                kind = "line"
                rep = " "
            else:
                close = clean.find("*/", cstart + 2)
                if close < 0:
                    rs = self.c2r(cstart)
                    raise GlslError(
                        Diagnostic(
                            "this /* comment is never closed: the file ends inside it",
                            self._raw_loc(rs, rs + 2),
                            rule=RULE,
                            help="add */ where the comment should end",
                        )
                    )
                cend = close + 2
                kind = "block"
                k = clean.count("\n", cstart, cend)
                rep = "\n" * k if k else " "
            rs, re_ = self.c2r(cstart), self.c2r(cend - 1) + 1
            self.comment_starts.append(olen)
            # located when read (as the AST's spans): the linter reads its own scan's comments
            self.comments.append(
                Comment(pending_location(self._raw_loc, rs, re_), raw[rs:re_], kind)
            )
            if rep == " ":
                self.bp_s.append(olen)
                self.bp_r.append(rs)
            else:
                q = cstart
                for i in range(len(rep)):
                    q = clean.find("\n", q) + 1
                    self.bp_s.append(olen + i)
                    self.bp_r.append(self.c2r(q - 1))
                    self.soft_newlines.add(olen + i)
            out.append(rep)
            olen += len(rep)
            pos = cend
        if not out or not out[-1].endswith("\n") or olen - 1 in self.soft_newlines:
            self._add_piece(olen, n, n)
            out.append("\n")
        self.stripped = "".join(out)
        self._nl_positions: list[int] | None = None
        self._nl_targets: list[int] | None = None

    # -- maps ------------------------------------------------------------------------------

    def c2r(self, c: int) -> int:
        return c + 2 * bisect_right(self.splices, c) if self.splices else c

    def _add_piece(self, s: int, a: int, b: int) -> None:
        """Clean text [a, b) is copied to stripped offset s."""
        self.bp_s.append(s)
        self.bp_r.append(self.c2r(a))
        if self.splices:
            i = bisect_right(self.splices, a)
            while i < len(self.splices) and self.splices[i] < b:
                q = self.splices[i]
                self.bp_s.append(s + q - a)
                self.bp_r.append(self.c2r(q))
                i += 1

    def s2r(self, s: int) -> int:
        i = bisect_right(self.bp_s, s) - 1
        if i < 0:
            return s
        return self.bp_r[i] + (s - self.bp_s[i])

    def _raw_pos(self, r: int) -> tuple[int, int]:
        r = min(r, len(self.raw))
        line = bisect_right(self.line_starts, r)
        return line, r - self.line_starts[line - 1] + 1

    def _raw_loc(self, rs: int, re_: int) -> Location:
        line, col = self._raw_pos(rs)
        eline, ecol = self._raw_pos(max(re_ - 1, rs))
        return Location(self.path, line, col, eline, ecol + (1 if re_ > rs else 0))

    def point(self, s: int) -> Location:
        line, col = self._raw_pos(self.s2r(s))
        return Location(self.path, line, col)

    def span(self, s: int, e: int) -> Location:
        if e <= s:
            return self.point(s)
        # s2r(s) and s2r(e - 1), inlined (every AST node's location comes through here).
        bp_s = self.bp_s
        i = bisect_right(bp_s, s) - 1
        rs = self.bp_r[i] + (s - bp_s[i]) if i >= 0 else s
        i = bisect_right(bp_s, e - 1) - 1
        rl = self.bp_r[i] + (e - 1 - bp_s[i]) if i >= 0 else e - 1
        line_starts = self.line_starts
        line = bisect_right(line_starts, rs)
        ls = line_starts[line - 1]
        if line < len(line_starts) and rl >= line_starts[line]:
            eline, ecol = self._raw_pos(rl)
            return Location(self.path, line, rs - ls + 1, eline, ecol + 1)
        return Location(self.path, line, rs - ls + 1, line, rl - ls + 2)

    def line_of(self, s: int) -> int:
        return self._raw_pos(self.s2r(s))[0]

    # -- newlines --------------------------------------------------------------------------

    def newlines(self) -> list[int]:
        if self._nl_positions is None:
            self._nl_positions = [m.start() for m in _NEWLINE_RE.finditer(self.stripped)]
            if self.splices:  # the line after each newline, in the user's file
                self._nl_targets = [self.line_of(p) + 1 for p in self._nl_positions]
        return self._nl_positions

    def target_after(self, i: int) -> int:
        """The user's line number that follows the i-th newline of the stripped text."""
        return self._nl_targets[i] if self._nl_targets is not None else i + 2

    @property
    def lines_joined(self) -> bool:
        """Whether the stripped text has fewer lines than the user's (a backslash-newline joined
        some), once `newlines` has run: then `target_after` is not simply i + 2."""
        return self._nl_targets is not None
