"""The preprocessor's state while it reads a program: the macros, the directives' data, the current
unit and its open conditionals, and the expanded text with its segments (the map back to the user's
files). Expansion, directives and the driver read and change it; it writes the output.
"""

from __future__ import annotations

from bisect import bisect_right

from ...base.diagnostics import Diagnostic, GlslError, Location
from ...base.records import record
from ...base.regexes import compiled
from .result import Macro, PPResult, Segment
from .tokens import Token, lex_all
from .units import RULE, Comment, Unit

MAX_EXPANSION_DEPTH = 64  # nested macro expansions (and nested calls in arguments)
MAX_EXPANSION_TOKENS = 200_000  # tokens produced by all macro expansions together
# a predefined macro's name (stored: `re.fullmatch` would compile it at each start)
_NAME_RE = compiled(r"[A-Za-z_][A-Za-z0-9_]*")


@record
class Conditional:
    loc: Location  # the #if / #ifdef / #ifndef
    parent_active: bool
    taken: bool  # some group of this chain was (or is) active
    seen_else: bool = False


class PreprocessorState:
    """Everything the preprocessor knows between two lines; `preprocess` makes one per program."""

    out_line: int  # the output's line the next text lands on (from 1 in each unit: start_unit)

    def __init__(self, predefined: dict[str, str] | None, shadertoy: bool):
        self.shadertoy = shadertoy
        self.macros: dict[str, Macro] = {}
        base = {
            "GL_ES": "1",
            "__VERSION__": "300",
            "GL_FRAGMENT_PRECISION_HIGH": "1",
            "__LINE__": "",
            "__FILE__": "",
        }
        if shadertoy:
            base["HW_PERFORMANCE"] = "1"
        base.update(predefined or {})
        for name, value in base.items():
            if not _NAME_RE.fullmatch(name):
                raise ValueError(f"predefined macro name {name!r} is not an identifier")
            toks = lex_all(value, 0, len(value))
            self.macros[name] = Macro(name, None, tuple(t.text for t in toks), None, True, toks)
        self.version: int | None = None
        self.extensions: list[tuple[str, str, Location]] = []
        self.pragmas: list[tuple[str, Location]] = []
        self.comments: list[Comment] = []
        self.diagnostics: list[Diagnostic] = []
        self.out: list[str] = []
        self.out_len = 0
        self.seg_starts: list[int] = []
        self.segs: list[Segment] = []
        self.budget = MAX_EXPANSION_TOKENS
        self.hide_cache: dict[tuple[frozenset[str], str], frozenset[str]] = {}
        self.seen_code = False  # a token before #version?
        self.seen_tokens = False  # a line of code (not a directive) before an #extension?

    # -- output ----------------------------------------------------------------------------

    def emit(self, text: str, unit: Unit, start: int, end: int = -1) -> None:
        if not text:
            return
        if end < 0 and self.segs:
            last = self.segs[-1]
            if (
                last.end < 0
                and last.unit is unit
                and last.start + (self.out_len - last.out_start) == start
            ):
                self.out.append(text)
                self.out_len += len(text)
                return
        self.seg_starts.append(self.out_len)
        self.segs.append(Segment(self.out_len, unit, start, end))
        self.out.append(text)
        self.out_len += len(text)

    def emit_verbatim(self, u: Unit, a: int, b: int) -> None:
        """Copy stripped text [a, b), adding the newlines joined lines have lost."""
        if a >= b:
            return
        nls = u.newlines()
        i = bisect_right(nls, a - 1)
        text = u.stripped
        while i < len(nls) and nls[i] < b:
            k = nls[i]
            target = u.target_after(i)
            if target == self.out_line + 1 and not u.lines_joined:
                # Every further newline of the chunk is in step with the user's lines.
                j = bisect_right(nls, b - 1)
                self.emit(text[a:b], u, a)
                self.out_line += j - i
                return
            self.emit(text[a:k], u, a)
            self.emit("\n" * max(target - self.out_line, 1), u, k)
            self.out_line = max(target, self.out_line + 1)
            a = k + 1
            i += 1
        self.emit(text[a:b], u, a)

    def emit_blank(self, u: Unit, nl_index: int) -> None:
        """Empty lines up to and including the newline with index nl_index."""
        target = u.target_after(nl_index)
        n = max(target - self.out_line, 1)
        self.emit("\n" * n, u, u.newlines()[nl_index])
        self.out_line += n

    def mark_inactive(self, u: Unit, a: int, b: int) -> None:
        i = bisect_right(u.comment_starts, a - 1)
        while i < len(u.comment_starts) and u.comment_starts[i] < b:
            u.comments[i].active = False
            i += 1

    # -- errors ----------------------------------------------------------------------------

    def error(self, message: str, s: int, e: int, help: str | None = None) -> GlslError:
        return GlslError(Diagnostic(message, self.unit.span(s, e), rule=RULE, help=help))

    def token_error(self, message: str, t: Token, help: str | None = None) -> GlslError:
        return self.error(message, *t.span(), help=help)

    # -- units -----------------------------------------------------------------------------

    def start_unit(self, u: Unit) -> None:
        """Read `u` next: its own line numbers, #line state and conditionals; its comments kept."""
        self.unit = u
        self.out_line = 1
        self.line_delta = 0  # set by #line
        self.file_number = 0
        self.comments.extend(u.comments)
        self.conds: list[Conditional] = []
        self.cond_active = True

    def result(self) -> PPResult:
        """The program read so far, as the later stages take it."""
        text = "".join(self.out)
        return PPResult(
            text,
            self.version,
            self.extensions,
            self.pragmas,
            self.comments,
            self.macros,
            self.diagnostics,
            self.seg_starts,
            self.segs,
        )
