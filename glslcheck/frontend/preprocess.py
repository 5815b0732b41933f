"""The GLSL ES 3.00 preprocessor (spec section 3.4), with a map back to the user's files.

This module owns everything between the text of the Shadertoy tabs and the lexer:

- line continuations (backslash-newline) and comments, which are collected as `Comment`s;
- the directives `#define #undef #if #ifdef #ifndef #elif #else #endif #error #pragma
  #extension #version #line` and the null directive `#`;
- macro expansion as in C (argument pre-expansion, rescanning, a macro is never expanded
  inside its own expansion) without the `#` and `##` operators, which GLSL ES does not have;
- `PPResult.locate` / `locate_span`, which map an offset of the expanded text back to the
  user's file, line and column.

Several units (Shadertoy: the Common tab, then the pass's tab) are preprocessed in order as
one program: macros defined in an earlier unit are visible in later ones, while each unit
keeps its own line numbers, and a conditional opened in a unit must be closed in it (the
Common tab is also compiled on its own). Predefined macros: `GL_ES` 1, `__VERSION__` 300,
`GL_FRAGMENT_PRECISION_HIGH` 1, `__LINE__`, `__FILE__`, and in Shadertoy mode
`HW_PERFORMANCE` 1.

The expanded text keeps the user's layout: text without macros is copied as it is (so its
columns match the file), a comment becomes one space or, when it spans lines, as many
newlines; directive lines and lines in inactive `#if` groups become empty lines; each
expansion is written as its tokens separated by single spaces; when a logical line was
joined by backslash-newline (or a macro call spans lines), the missing newlines are added at
its end, so every line of the output starts at the user's line of the same number.
Offsets inside an expansion map to the whole outermost macro use (name to closing paren).

`#line N [M]` only changes what `__LINE__` and `__FILE__` expand to; locations keep pointing
at the real line of the user's file. `__LINE__` counts lines of the unit it is used in.

Runaway macros cannot hang or overflow the stack: more than MAX_EXPANSION_DEPTH nested
expansions, or more than MAX_EXPANSION_TOKENS tokens produced by expansion, is an error.

Errors raise `GlslError` with one `Diagnostic(rule="preprocessor")` located in the user's
file; warnings (a macro name with `__`) are collected in `PPResult.diagnostics`.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from heapq import heapify, heappop, heappush
from ..base.regexes import compiled
from ..base.diagnostics import Diagnostic, GlslError, Location, pending_location
from ..base.records import field, record
from ..shadertoy.sources import Source

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up (issue 18)
if TYPE_CHECKING:
    from typing import Iterator

__all__ = ["preprocess", "PPResult", "Comment", "Macro", "MAX_EXPANSION_DEPTH", "MAX_EXPANSION_TOKENS"]

# The first parameter of the entry function modelled for a `mainImage` macro (see _wrapper_call):
# the checker knows that function's body by it (it is compiled in the pass, never in Common alone).
WRAPPER_COLOR = "glslcheck_color"
MAX_EXPANSION_DEPTH = 64  # nested macro expansions (and nested calls in arguments)
MAX_EXPANSION_TOKENS = 200_000  # tokens produced by all macro expansions together
MAX_IF_NESTING = 100  # parentheses and unary operators in one #if expression

RULE = "preprocessor"

# ---------------------------------------------------------------------------------------------
# Data the rest of glslcheck reads


@record
class Comment:
    """One comment of the user's text, as written (`//...` or `/*...*/`)."""

    loc: Location  # the span of the whole comment
    text: str
    kind: str  # "line" | "block"
    active: bool = True  # False inside an #if group that is skipped


@record
class Macro:
    """A macro: `params` is None for an object-like macro; `body` holds the token texts."""

    name: str
    params: tuple[str, ...] | None
    body: tuple[str, ...]
    loc: Location | None = None  # where it was defined; None for a predefined macro
    predefined: bool = False
    tokens: list = field(default_factory=list, repr=False, compare=False)

    @property
    def dynamic(self) -> bool:  # __LINE__ and __FILE__
        return self.name in ("__LINE__", "__FILE__")


@record
class _Segment:
    out_start: int
    unit: "_Unit"
    start: int  # stripped offset; for a macro use, the start of the use
    end: int = -1  # -1: linear copy of the text; otherwise the end of the macro use


@record(slots=False)
class PPResult:
    """The preprocessed program and everything the later stages need from the directives."""

    text: str
    version: int | None
    extensions: list[tuple[str, str, Location]]
    pragmas: list[tuple[str, Location]]
    comments: list[Comment]
    macros: dict[str, Macro]
    diagnostics: list[Diagnostic] = field(default_factory=list)
    _seg_starts: list[int] = field(default_factory=list, repr=False)
    _segs: list[_Segment] = field(default_factory=list, repr=False)

    def _seg(self, offset: int) -> tuple[_Segment, int]:
        i = bisect_right(self._seg_starts, offset) - 1
        seg = self._segs[max(i, 0)]
        return seg, offset - seg.out_start

    def _seg_len(self, seg: _Segment) -> int:
        i = bisect_right(self._seg_starts, seg.out_start)
        return (self._seg_starts[i] if i < len(self._seg_starts) else len(self.text)) - seg.out_start

    def locate(self, offset: int) -> Location:
        """The user's file, line and column of `offset` in `text`: a point for copied text, the
        span of the whole (outermost) macro use for text that came from an expansion."""
        if not self._segs:
            return Location("<empty>", 1, 1)
        seg, delta = self._seg(offset)
        if seg.end >= 0:
            return seg.unit.span(seg.start, seg.end)
        return seg.unit.point(seg.start + delta)

    def locate_span(self, start: int, end: int) -> Location:
        """The span in the user's file of `text[start:end]` (a point when end <= start)."""
        if end <= start or not self._segs:
            return self.locate(start)
        # _seg and _seg_len, inlined: the parser locates every AST node through here. The
        # segments' starts increase strictly (each holds some text), from 0.
        starts = self._seg_starts
        i = bisect_right(starts, start) - 1
        seg = self._segs[i]
        if seg.end < 0 and i >= 0 and end <= (starts[i + 1] if i + 1 < len(starts) else len(self.text)):
            # Both ends in one copied piece of text: the common case of a token.
            shift = seg.start - seg.out_start
            return seg.unit.span(start + shift, end + shift)
        first = self.locate(start)
        last_seg, delta = self._seg(end - 1)
        if last_seg.end >= 0:
            last = last_seg.unit.span(last_seg.start, last_seg.end)
            return first.span_to(last)
        p = last_seg.unit.point(last_seg.start + delta)
        return Location(first.path, first.line, first.column, p.line, p.column + 1)


# ---------------------------------------------------------------------------------------------
# Tokens

ID, NUM, OP, OTHER = "id", "num", "op", "other"

_NUMBER = (
    r"(?:0[xX][0-9A-Fa-f]*|(?:[0-9]+\.[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|[0-9]+(?:[eE][+-]?[0-9]+)?)"
    r"[A-Za-z0-9_]*"
)
_OPERATOR = (
    r"<<=|>>=|\+\+|--|<<|>>|<=|>=|==|!=|&&|\|\||\^\^|\+=|-=|\*=|/=|%=|&=|\^=|\|=|\#\#"
    r"|[-+*/%<>=!~&|^?:;,.()\[\]{}\#]"
)
_WS = " \t\n\v\f\r"
_TOKEN_RE = compiled(
    rf"[{_WS}]*(?:(?P<id>[A-Za-z_][A-Za-z0-9_]*)|(?P<num>{_NUMBER})|(?P<op>{_OPERATOR})|(?P<other>[^{_WS}]))",
    re.S,
)
_LEAD_WS_RE = compiled(rf"[{_WS}]*")
_COMMENT_RE = compiled(r"//|/\*")
_NEWLINE_RE = compiled("\n")
_EMPTY: frozenset[str] = frozenset()


class _Tok:
    """A pp-token. `start`/`end` are offsets in the stripped text of the unit it was read from;
    `src` is the span of the macro use it came from (None for a token read from the file);
    `hide` holds the macros it must not be expanded by again."""

    __slots__ = ("kind", "text", "start", "end", "ws", "hide", "src")

    def __init__(self, kind, text, start, end, ws=False, hide=None, src=None):
        self.kind = kind
        self.text = text
        self.start = start
        self.end = end
        self.ws = ws
        self.hide = hide
        self.src = src

    def span(self) -> tuple[int, int]:
        return self.src if self.src is not None else (self.start, self.end)

    def __repr__(self) -> str:  # for debugging and test failure messages
        return f"<{self.kind} {self.text!r}>"


def _lex(text: str, pos: int, end: int) -> _Tok | None:
    """The next token of `text[pos:end]`, or None at the end."""
    m = _TOKEN_RE.match(text, pos, end)
    if m is None:
        return None
    kind = m.lastgroup
    t = m.group(kind)
    e = m.end()
    s = e - len(t)
    return _Tok(kind, t, s, e, s > pos)


def _lex_all(text: str, pos: int, end: int) -> list[_Tok]:
    out = []
    while True:
        t = _lex(text, pos, end)
        if t is None:
            return out
        out.append(t)
        pos = t.end


# ---------------------------------------------------------------------------------------------
# One unit: continuations and comments removed, with the map back to the raw text


class _Unit:
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
                    raise GlslError(Diagnostic(
                        "this /* comment is never closed: the file ends inside it",
                        self._raw_loc(rs, rs + 2), rule=RULE,
                        help="add */ where the comment should end"))
                cend = close + 2
                kind = "block"
                k = clean.count("\n", cstart, cend)
                rep = "\n" * k if k else " "
            rs, re_ = self.c2r(cstart), self.c2r(cend - 1) + 1
            self.comment_starts.append(olen)
            # located when read (as the AST's spans): the linter reads its own scan's comments
            self.comments.append(Comment(pending_location(self._raw_loc, rs, re_), raw[rs:re_], kind))
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


# ---------------------------------------------------------------------------------------------
# Macro expansion input


class _Input:
    """Tokens to expand: a stack of pushed-back tokens, then (at the top level) the file."""

    __slots__ = ("stack", "text", "pos", "end", "src_end", "peeked")

    def __init__(self, tokens: list[_Tok], text: str = "", pos: int = 0, end: int = 0):
        self.stack = tokens[::-1]
        self.text = text
        self.pos = pos
        self.end = end
        self.src_end = pos  # end of the last token consumed from the file
        self.peeked: _Tok | None = None

    def next(self) -> _Tok | None:
        if self.stack:
            return self.stack.pop()
        t = self.peeked or _lex(self.text, self.pos, self.end)
        self.peeked = None
        if t is not None:
            self.pos = self.src_end = t.end
        return t

    def peek_lparen(self) -> bool:
        if self.stack:
            return self.stack[-1].text == "("
        if self.peeked is None:
            self.peeked = _lex(self.text, self.pos, self.end)
        return self.peeked is not None and self.peeked.text == "("


# ---------------------------------------------------------------------------------------------
# The preprocessor


_BEHAVIORS = ("require", "enable", "warn", "disable")
_COND = ("if", "ifdef", "ifndef", "elif", "else", "endif")
_BINARY_PREC = {
    "||": 1, "&&": 2, "|": 3, "^": 4, "&": 5, "==": 6, "!=": 6,
    "<": 7, ">": 7, "<=": 7, ">=": 7, "<<": 8, ">>": 8, "+": 9, "-": 9, "*": 10, "/": 10, "%": 10,
}
_INT_RE = compiled(r"0[xX][0-9A-Fa-f]+|0[0-7]*|[1-9][0-9]*")
_NAME_RE = compiled(r"[A-Za-z_][A-Za-z0-9_]*")  # a predefined macro's name (stored: `re.fullmatch` compiled it at each start)
_INVARIANT_ALL_RE = compiled(r"STDGL[ \t]+invariant[ \t]*\([ \t]*all[ \t]*\)[ \t]*")


def _wrap32(v: int) -> int:
    v &= 0xFFFFFFFF
    return v - 0x100000000 if v & 0x80000000 else v


@record
class _Cond:
    loc: Location  # the #if / #ifdef / #ifndef
    parent_active: bool
    taken: bool  # some group of this chain was (or is) active
    seen_else: bool = False


class _Preprocessor:
    def __init__(self, predefined: dict[str, str] | None, shadertoy: bool):
        self.shadertoy = shadertoy
        self.macros: dict[str, Macro] = {}
        base = {"GL_ES": "1", "__VERSION__": "300", "GL_FRAGMENT_PRECISION_HIGH": "1", "__LINE__": "", "__FILE__": ""}
        if shadertoy:
            base["HW_PERFORMANCE"] = "1"
        base.update(predefined or {})
        for name, value in base.items():
            if not _NAME_RE.fullmatch(name):
                raise ValueError(f"predefined macro name {name!r} is not an identifier")
            toks = _lex_all(value, 0, len(value))
            self.macros[name] = Macro(name, None, tuple(t.text for t in toks), None, True, toks)
        self.version: int | None = None
        self.extensions: list[tuple[str, str, Location]] = []
        self.pragmas: list[tuple[str, Location]] = []
        self.comments: list[Comment] = []
        self.diagnostics: list[Diagnostic] = []
        self.out: list[str] = []
        self.out_len = 0
        self.seg_starts: list[int] = []
        self.segs: list[_Segment] = []
        self.budget = MAX_EXPANSION_TOKENS
        self.hide_cache: dict[tuple[frozenset[str], str], frozenset[str]] = {}
        self.seen_code = False  # a token before #version?
        self.seen_tokens = False  # a line of code (not a directive) before an #extension?

    # -- output ----------------------------------------------------------------------------

    def _emit(self, text: str, unit: _Unit, start: int, end: int = -1) -> None:
        if not text:
            return
        if end < 0 and self.segs:
            last = self.segs[-1]
            if last.end < 0 and last.unit is unit and last.start + (self.out_len - last.out_start) == start:
                self.out.append(text)
                self.out_len += len(text)
                return
        self.seg_starts.append(self.out_len)
        self.segs.append(_Segment(self.out_len, unit, start, end))
        self.out.append(text)
        self.out_len += len(text)

    def _emit_verbatim(self, u: _Unit, a: int, b: int) -> None:
        """Copy stripped text [a, b), adding the newlines joined lines have lost."""
        if a >= b:
            return
        nls = u.newlines()
        i = bisect_right(nls, a - 1)
        text = u.stripped
        while i < len(nls) and nls[i] < b:
            k = nls[i]
            target = u.target_after(i)
            if target == self.out_line + 1 and u._nl_targets is None:
                # Every further newline of the chunk is in step with the user's lines.
                j = bisect_right(nls, b - 1)
                self._emit(text[a:b], u, a)
                self.out_line += j - i
                return
            self._emit(text[a:k], u, a)
            self._emit("\n" * max(target - self.out_line, 1), u, k)
            self.out_line = max(target, self.out_line + 1)
            a = k + 1
            i += 1
        self._emit(text[a:b], u, a)

    def _emit_blank(self, u: _Unit, nl_index: int) -> None:
        """Empty lines up to and including the newline with index nl_index."""
        target = u.target_after(nl_index)
        n = max(target - self.out_line, 1)
        self._emit("\n" * n, u, u.newlines()[nl_index])
        self.out_line += n

    # -- errors ----------------------------------------------------------------------------

    def _error(self, message: str, s: int, e: int, help: str | None = None) -> GlslError:
        return GlslError(Diagnostic(message, self.unit.span(s, e), rule=RULE, help=help))

    def _tok_error(self, message: str, t: _Tok, help: str | None = None) -> GlslError:
        return self._error(message, *t.span(), help=help)

    # -- driver ----------------------------------------------------------------------------

    def run(self, units: list[Source]) -> PPResult:
        for index, src in enumerate(units):
            self._unit(_Unit(src, index))
        if self.shadertoy and units and units[-1].tab != "Common":
            self._wrapper_call(len(units))
        text = "".join(self.out)
        return PPResult(text, self.version, self.extensions, self.pragmas, self.comments, self.macros,
                        self.diagnostics, self.seg_starts, self.segs)

    def _wrapper_call(self, index: int) -> None:
        """Shadertoy compiles its wrapper after the user's code, so a user macro `mainImage(O, U)`
        (code golf: `#define mainImage(O, U) O = ...`) expands inside the wrapper's call
        `mainImage(color, gl_FragCoord.xy);`. Model that call as the entry function: its header
        is written as it is, its body is the call expanded by the user's macro (placed on the
        macro's line, so messages point at it)."""
        macro = self.macros.get("mainImage")
        if macro is None or macro.params is None or len(macro.params) != 2 or macro.loc is None:
            return
        pad = "\n" * (macro.loc.line - 1)
        header = Source(macro.loc.path, pad + f"void mainImage(out vec4 {WRAPPER_COLOR}, in vec2 glslcheck_coord) {{\n")
        body = Source(macro.loc.path, pad + f"{WRAPPER_COLOR} = vec4(1e20); mainImage({WRAPPER_COLOR}, glslcheck_coord); }}\n")
        del self.macros["mainImage"]  # the header names the function; only the call expands
        self._unit(_Unit(header, index))
        self.macros["mainImage"] = macro
        self._unit(_Unit(body, index + 1))

    def _unit(self, u: _Unit) -> None:
        self.unit = u
        self.out_line = 1
        self.line_delta = 0  # set by #line
        self.file_number = 0
        self.comments.extend(u.comments)
        self.conds: list[_Cond] = []
        self._cond_active = True
        text = u.stripped
        nls = u.newlines()
        soft = u.soft_newlines
        run_start = None  # start of the pending run of active text lines
        run_end = 0
        start = 0
        for i, nl in enumerate(nls):
            if nl in soft:
                continue
            f = _LEAD_WS_RE.match(text, start, nl).end()
            active = self._cond_active
            if f < nl and text[f] == "#":
                if run_start is not None:
                    self._text_run(u, run_start, run_end)
                    run_start = None
                self._directive(u, start, f, nl, active)
                self._emit_blank(u, i)
            elif active:
                if run_start is None:
                    run_start = start
                run_end = nl + 1
                if f < nl and not self.seen_code:
                    self.seen_code = True
                if f < nl:
                    self.seen_tokens = True
            else:
                self._mark_inactive(u, start, nl)
                self._emit_blank(u, i)
            start = nl + 1
        if run_start is not None:
            self._text_run(u, run_start, run_end)
        if self.conds:
            c = self.conds[-1]
            raise GlslError(Diagnostic("this #if is never closed: add #endif", c.loc, rule=RULE))

    def _mark_inactive(self, u: _Unit, a: int, b: int) -> None:
        i = bisect_right(u.comment_starts, a - 1)
        while i < len(u.comment_starts) and u.comment_starts[i] < b:
            u.comments[i].active = False
            i += 1

    # -- text lines and macro expansion ----------------------------------------------------

    def _text_run(self, u: _Unit, a: int, b: int) -> None:
        """Expand the macros of active text lines [a, b) and write them out."""
        text = u.stripped
        macros = self.macros
        pos = a
        for s, name in _macro_names_at(text, macros, a, b):
            if s < pos:
                continue
            macro = macros[name]
            if _inside_number(text, s):
                continue
            e = s + len(name)
            inp = _Input([], text, e, b)
            if macro.params is not None and not inp.peek_lparen():
                continue
            out: list[_Tok] = []
            self._step(_Tok(ID, name, s, e), inp, out, 0)
            while inp.stack:
                self._step(inp.stack.pop(), inp, out, 0)
            use_end = inp.src_end
            self._emit_verbatim(u, pos, s)
            lead = "" if s == a or text[s - 1] in _WS else " "
            trail = "" if text[use_end] in _WS else " "
            self._emit(lead + " ".join(t.text for t in out) + trail, u, s, use_end)
            pos = use_end
        self._emit_verbatim(u, pos, b)

    def _expand_list(self, tokens: list[_Tok], depth: int) -> list[_Tok]:
        """Fully macro-expand a token list on its own (a macro argument, an #if line)."""
        if depth > MAX_EXPANSION_DEPTH:
            t = tokens[0] if tokens else None
            raise self._expansion_error("deep", t)
        inp = _Input(tokens)
        out: list[_Tok] = []
        while inp.stack:
            self._step(inp.stack.pop(), inp, out, depth)
        return out

    def _expansion_error(self, what: str, t: _Tok | None) -> GlslError:
        s, e = t.span() if t is not None else (0, 0)
        return self._error(
            f"macro expansion is too {'deep' if what == 'deep' else 'large'}"
            + (f" (more than {MAX_EXPANSION_DEPTH} nested expansions)" if what == "deep"
               else f" (more than {MAX_EXPANSION_TOKENS} tokens)"),
            s, e, help="a macro probably expands to itself through other macros, or doubles at each level")

    def _step(self, t: _Tok, inp: _Input, out: list[_Tok], depth: int) -> None:
        """Expand t if it names a macro (pushing the result back onto inp), else output it."""
        name = t.text
        macro = self.macros.get(name) if t.kind == ID else None
        if macro is None or (t.hide is not None and name in t.hide):
            out.append(t)
            return
        hide = t.hide or _EMPTY
        if macro.params is None:
            use = t.span()
            body = macro.tokens
            if macro.dynamic:
                line = self.unit.line_of(use[0]) + self.line_delta
                value = line if name == "__LINE__" else self.file_number
                body = [_Tok(NUM, str(value), 0, 0)]
        else:
            if not inp.peek_lparen():
                out.append(t)
                return
            inp.next()
            args, rp = self._collect_args(t, inp)
            nparams = len(macro.params)
            if nparams == 0 and args == [[]]:
                args = []
            if len(args) != nparams:
                s, e = t.span()[0], rp.span()[1]
                raise self._error(
                    f"macro '{name}' takes {nparams} argument{'s' if nparams != 1 else ''} "
                    f"but {len(args)} {'were' if len(args) != 1 else 'was'} given", s, e,
                    help=f"'{name}' is defined at {macro.loc}" if macro.loc else None)
            hide = hide & (rp.hide or _EMPTY)
            use = (t.span()[0], rp.span()[1])
            index = {p: i for i, p in enumerate(macro.params)}
            expanded: dict[int, list[_Tok]] = {}
            body = []
            for b in macro.tokens:
                i = index.get(b.text) if b.kind == ID else None
                if i is None:
                    body.append(b)
                else:
                    if i not in expanded:
                        expanded[i] = self._expand_list(args[i], depth + 1)
                    body.extend(expanded[i])
        key = (hide, name)
        new_hide = self.hide_cache.get(key)
        if new_hide is None:
            new_hide = self.hide_cache[key] = hide | {name}
            if len(new_hide) > MAX_EXPANSION_DEPTH:
                raise self._expansion_error("deep", t)
        hide = new_hide
        self.budget -= len(body)
        if self.budget < 0:
            raise self._expansion_error("large", t)
        stack = inp.stack
        for b in reversed(body):
            stack.append(_Tok(b.kind, b.text, use[0], use[1], b.ws,
                              hide if b.hide is None else (b.hide | hide), use))

    def _collect_args(self, name: _Tok, inp: _Input) -> tuple[list[list[_Tok]], _Tok]:
        args: list[list[_Tok]] = [[]]
        level = 0
        while True:
            t = inp.next()
            if t is None:
                raise self._tok_error(
                    f"the argument list of macro '{name.text}' is not closed: a ')' is missing", name,
                    help="a macro call in a directive must end on the same line" if inp.end == 0 else None)
            if t.kind == OP:
                if t.text == "(":
                    level += 1
                elif t.text == ")":
                    if level == 0:
                        return args, t
                    level -= 1
                elif t.text == "," and level == 0:
                    args.append([])
                    continue
            args[-1].append(t)

    # -- directives ------------------------------------------------------------------------

    def _directive(self, u: _Unit, start: int, hash_pos: int, nl: int, active: bool) -> None:
        text = u.stripped
        name_tok = _lex(text, hash_pos + 1, nl)
        if name_tok is None:
            return  # the null directive
        name = name_tok.text if name_tok.kind == ID else ""
        if not active:
            if not (name in ("elif", "else", "endif") and self.conds and self.conds[-1].parent_active):
                self._mark_inactive(u, start, nl)
            if name in _COND:
                self._conditional(name, name_tok, _lex_all(text, name_tok.end, nl), hash_pos, nl, active)
            return
        if name in ("error", "pragma"):
            rest = text[name_tok.end:nl].strip(_WS)
            loc = u.span(hash_pos, nl)
            if name == "error":
                raise GlslError(Diagnostic(f"#error: {rest}" if rest else "#error", loc, rule=RULE))
            if (self.version or (300 if self.shadertoy else 100)) == 300 and _INVARIANT_ALL_RE.fullmatch(rest):
                # GLSL ES 3.00 section 4.6.1: only a vertex shader's outputs can be invariant;
                # Mesa: "pragma `invariant(all)' cannot be used in a fragment shader".
                raise GlslError(Diagnostic("#pragma STDGL invariant(all) cannot be used in a fragment shader "
                                           "(GLSL ES 3.00 section 4.6.1)", loc, rule=RULE,
                                           help="remove it: a fragment shader's outputs are never invariant"))
            self.pragmas.append((rest, loc))
            return
        toks = _lex_all(text, name_tok.end, nl)
        for t in toks:
            if t.kind == OTHER:
                raise self._tok_error(f"unexpected character {t.text!r} in a preprocessor directive", t)
        if name in _COND:
            self._conditional(name, name_tok, toks, hash_pos, nl, active)
        elif name == "define":
            self._define(toks, name_tok)
        elif name == "undef":
            if not toks or toks[0].kind != ID:
                raise self._tok_error("#undef needs a macro name", toks[0] if toks else name_tok)
            self._check_name(toks[0], "undefine")
            if len(toks) > 1:
                raise self._tok_error("#undef takes a single macro name", toks[1])
            self.macros.pop(toks[0].text, None)
        elif name == "extension":
            self._extension(toks, name_tok, hash_pos, nl)
        elif name == "version":
            self._version(toks, name_tok, hash_pos, nl)
        elif name == "line":
            self._line(toks, name_tok, nl)
        else:
            raise self._tok_error(
                f"unknown preprocessor directive '#{name_tok.text}'", name_tok,
                help="GLSL ES has #define #undef #if #ifdef #ifndef #elif #else #endif "
                     "#error #pragma #extension #version #line")
        self.seen_code = self.seen_code or name != "version"

    def _check_name(self, t: _Tok, verb: str) -> None:
        n = t.text
        if n.startswith("GL_"):
            raise self._tok_error(f"cannot {verb} '{n}': macro names starting with 'GL_' are reserved", t)
        if n == "defined":
            raise self._tok_error(f"cannot {verb} 'defined'", t)
        if n in ("__LINE__", "__FILE__", "__VERSION__"):
            raise self._tok_error(f"cannot {verb} the predefined macro '{n}'", t)
        if "__" in n:
            d = Diagnostic(f"macro names containing '__' are reserved: '{n}'", self.unit.span(t.start, t.end),
                           severity="warning", rule=RULE)
            if self.version == 100:  # GLSL ES 1.00 makes it an error
                raise GlslError(Diagnostic(d.message, d.loc, rule=RULE))
            self.diagnostics.append(d)

    def _define(self, toks: list[_Tok], directive: _Tok) -> None:
        if not toks or toks[0].kind != ID:
            raise self._tok_error("#define needs a macro name", toks[0] if toks else directive)
        nt = toks[0]
        self._check_name(nt, "define")
        params: tuple[str, ...] | None = None
        i = 1
        if len(toks) > 1 and toks[1].text == "(" and not toks[1].ws:
            plist: list[str] = []
            i = 2
            while True:
                if i >= len(toks):
                    raise self._tok_error(f"the parameter list of macro '{nt.text}' is not closed: a ')' is missing", nt)
                t = toks[i]
                if t.text == ")" and not plist:
                    i += 1
                    break
                if t.kind != ID:
                    raise self._tok_error(f"expected a parameter name in macro '{nt.text}', found '{t.text}'", t)
                if t.text in plist:
                    raise self._tok_error(f"macro '{nt.text}' has two parameters named '{t.text}'", t)
                plist.append(t.text)
                if i + 1 >= len(toks):
                    raise self._tok_error(f"the parameter list of macro '{nt.text}' is not closed: a ')' is missing", nt)
                sep = toks[i + 1]
                i += 2
                if sep.text == ")":
                    break
                if sep.text != ",":
                    raise self._tok_error(f"expected ',' or ')' in the parameters of macro '{nt.text}', found '{sep.text}'", sep)
            params = tuple(plist)
        body = toks[i:]
        for t in body:
            if t.text in ("#", "##"):
                raise self._tok_error(
                    f"the '{t.text}' operator is not allowed in GLSL ES", t,
                    help="GLSL ES macros cannot turn arguments into strings or paste tokens")
        new = Macro(nt.text, params, tuple(t.text for t in body), self.unit.span(nt.start, nt.end), False, body)
        old = self.macros.get(nt.text)
        if old is not None and (
            old.params != params or old.body != new.body
            or [t.ws for t in old.tokens[1:]] != [t.ws for t in body[1:]]
        ):
            where = f" at {old.loc}" if old.loc else " (it is predefined)"
            raise self._tok_error(
                f"macro '{nt.text}' is already defined{where} with a different body", nt,
                help=f"use #undef {nt.text} first to change it")
        self.macros[nt.text] = new

    def _conditional(self, name: str, nt: _Tok, toks: list[_Tok], hash_pos: int, nl: int, active: bool) -> None:
        """#if #ifdef #ifndef #elif #else #endif; `active`: is the group holding this line active?"""
        loc_s, loc_e = hash_pos, nt.end
        if name in ("if", "ifdef", "ifndef"):
            parent = active
            value = False
            if parent:
                if name == "if":
                    value = self._eval_if(toks, nt)
                else:
                    if not toks or toks[0].kind != ID:
                        raise self._tok_error(f"#{name} needs a macro name", toks[0] if toks else nt)
                    if len(toks) > 1:
                        raise self._tok_error(f"unexpected '{toks[1].text}' after #{name} {toks[0].text}", toks[1])
                    value = (toks[0].text in self.macros) == (name == "ifdef")
            self.conds.append(_Cond(self.unit.span(loc_s, loc_e), parent, value))
            self._cond_active = value
            return
        if not self.conds:
            raise self._error(f"#{name} without a matching #if", loc_s, loc_e)
        c = self.conds[-1]
        if name == "endif":
            if toks and c.parent_active:
                raise self._tok_error(f"unexpected '{toks[0].text}' after #endif", toks[0])
            self.conds.pop()
            self._cond_active = c.parent_active  # back in the enclosing group
            return
        if c.seen_else:
            raise self._error(f"#{name} after #else", loc_s, loc_e)
        if name == "else":
            if toks and c.parent_active:
                raise self._tok_error(f"unexpected '{toks[0].text}' after #else", toks[0])
            c.seen_else = True
            self._cond_active = c.parent_active and not c.taken
            c.taken = True
            return
        # elif
        if c.parent_active and not c.taken:
            value = self._eval_if(toks, nt)
            c.taken = value
            self._cond_active = value
        else:
            self._cond_active = False

    # #if expressions ------------------------------------------------------------------------

    def _eval_if(self, toks: list[_Tok], directive: _Tok) -> bool:
        if not toks:
            raise self._tok_error(f"#{directive.text} needs an expression", directive)
        # `defined X` and `defined(X)` are resolved before macro expansion.
        pre: list[_Tok] = []
        i = 0
        while i < len(toks):
            t = toks[i]
            if t.kind == ID and t.text == "defined":
                if i + 1 < len(toks) and toks[i + 1].kind == ID:
                    target, i = toks[i + 1], i + 2
                    end = target.end
                elif (i + 3 < len(toks) and toks[i + 1].text == "(" and toks[i + 2].kind == ID
                      and toks[i + 3].text == ")"):
                    target, end, i = toks[i + 2], toks[i + 3].end, i + 4
                else:
                    raise self._tok_error("'defined' needs a macro name: defined NAME or defined(NAME)", t)
                pre.append(_Tok(NUM, "1" if target.text in self.macros else "0", t.start, end, t.ws))
                continue
            pre.append(t)
            i += 1
        expr = self._expand_list(pre, 0)
        if not expr:
            raise self._tok_error(f"#{directive.text} needs an expression (the macros expand to nothing)", directive)
        ev = _IfEvaluator(self, expr, directive)
        value = ev.expression(1, True, 0)
        if ev.i < len(expr):
            t = expr[ev.i]
            raise self._tok_error(f"unexpected '{t.text}' in the #{directive.text} expression", t)
        return value != 0

    # #extension, #version, #line --------------------------------------------------------

    def _extension(self, toks: list[_Tok], nt: _Tok, hash_pos: int, nl: int) -> None:
        # GLSL ES 3.00 3.4: #extension comes before any code. Shadertoy puts its precision and
        # uniform declarations before a tab's text, so in a tab it always comes after code;
        # WebGL 2 (ANGLE) and Mesa reject the program.
        if self.shadertoy:
            raise self._error(
                "#extension is not allowed in a Shadertoy tab: Shadertoy's own declarations come first, "
                "and an #extension after code is rejected by WebGL 2", hash_pos, nl)
        if self.seen_tokens:
            raise self._error("#extension must come before any code in the shader", hash_pos, nl)
        shape = [t.kind for t in toks[:3]] == [ID, OP, ID] and toks[1].text == ":"
        if not shape or len(toks) != 3:
            bad = toks[3] if shape else (toks[0] if toks else nt)
            raise self._tok_error("#extension must read '#extension name : behavior'", bad)
        ext, behavior = toks[0].text, toks[2].text
        if behavior not in _BEHAVIORS:
            raise self._tok_error(
                f"unknown #extension behavior '{behavior}': use require, enable, warn or disable", toks[2])
        if ext == "all" and behavior in ("require", "enable"):
            raise self._tok_error(f"'#extension all' can only be 'warn' or 'disable', not '{behavior}'", toks[2])
        self.extensions.append((ext, behavior, self.unit.span(hash_pos, toks[2].end)))

    def _version(self, toks: list[_Tok], nt: _Tok, hash_pos: int, nl: int) -> None:
        if self.shadertoy:
            raise self._error("Shadertoy adds #version 300 es itself; remove this line", hash_pos, nl)
        if self.version is not None:
            raise self._error("a second #version line", hash_pos, nl)
        if self.seen_code or self.unit.index > 0:
            raise self._error("#version must be the first line of the shader (only comments may come before it)",
                              hash_pos, nl)
        words = [t.text for t in toks]
        if words == ["300", "es"]:
            self.version = 300
        elif words == ["100"]:
            self.version = 100
        elif words == ["300"]:
            raise self._error("GLSL ES 3.00 is written '#version 300 es'", hash_pos, nl)
        else:
            raise self._error(
                f"unsupported version '#version {' '.join(words)}': glslcheck reads GLSL ES 3.00 "
                "('#version 300 es') and 1.00 ('#version 100')", hash_pos, nl)
        self.macros["__VERSION__"] = Macro("__VERSION__", None, (str(self.version),), None, True,
                                           [_Tok(NUM, str(self.version), 0, 0)])

    def _line(self, toks: list[_Tok], nt: _Tok, nl: int) -> None:
        expr = self._expand_list(toks, 0)
        nums = []
        for t in expr:
            # GLSL ES 3.00 section 3.4: "constant integer expressions"; an integer literal in
            # any base (decimal, octal 010, hex 0x10) is one, as Mesa and glslang accept.
            if t.kind != NUM or not _INT_RE.fullmatch(t.text):
                raise self._tok_error(f"#line takes a line number and an optional source number, not '{t.text}'", t)
            nums.append(int(t.text, 8) if t.text.startswith("0") and t.text[1:].isdigit() else int(t.text, 0))
        if not 1 <= len(nums) <= 2:
            raise self._tok_error("#line takes a line number and an optional source number", nt)
        next_line = self.unit.line_of(nl) + 1
        self.line_delta = nums[0] - next_line
        if len(nums) == 2:
            self.file_number = nums[1]


def _macro_names_at(text: str, macros: dict, a: int, b: int) -> Iterator[tuple[int, str]]:
    """(offset, name) of each identifier in text[a:b] that names a macro, in order: what a
    regular expression finding every identifier, `(?<![A-Za-z0-9_])[A-Za-z_][A-Za-z0-9_]*`,
    and a look-up of each would find, with `str.find` per macro name instead of a match per
    identifier (the lab's programs define one or two
    macros and have thousands of identifiers). A name counts where it is a whole identifier:
    no letter, digit or `_` on either side (an identifier reaching `b` ends there)."""
    heap = []
    for name in macros:
        s = _find_identifier(text, name, a, b)
        if s >= 0:
            heap.append((s, name))
    heapify(heap)
    while heap:
        s, name = heappop(heap)
        yield s, name
        s = _find_identifier(text, name, s + len(name), b)
        if s >= 0:
            heappush(heap, (s, name))


def _find_identifier(text: str, name: str, start: int, end: int) -> int:
    """The first offset in [start, end) where `name` stands as a whole identifier, or -1."""
    n = len(name)
    i = text.find(name, start, end)
    while i >= 0:
        if (i == 0 or text[i - 1] not in _WORD_CHARS) and (i + n == end or text[i + n] not in _WORD_CHARS):
            return i
        i = text.find(name, i + 1, end)
    return -1


_WORD_CHARS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_")


def _inside_number(text: str, s: int) -> bool:
    """Is the identifier-looking text at s the tail of a number such as `1.e5` or `2.f`?"""
    if s == 0 or text[s - 1] != ".":
        return False
    j = s - 1
    k = j
    while k > 0 and (text[k - 1].isalnum() or text[k - 1] == "_") and text[k - 1].isascii():
        k -= 1
    return k < j and text[k].isdigit()


class _IfEvaluator:
    """Evaluates the tokens of an #if line (after expansion) with 32-bit integer arithmetic."""

    def __init__(self, pp: _Preprocessor, toks: list[_Tok], directive: _Tok):
        self.pp = pp
        self.toks = toks
        self.i = 0
        self.directive = directive

    def _peek(self) -> _Tok | None:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def _fail(self, message: str, t: _Tok | None) -> GlslError:
        return self.pp._tok_error(message, t or self.toks[-1])

    def expression(self, min_prec: int, live: bool, nesting: int) -> int:
        lhs = self.unary(live, nesting)
        while True:
            t = self._peek()
            prec = _BINARY_PREC.get(t.text) if t is not None and t.kind == OP else None
            if prec is None or prec < min_prec:
                return lhs
            self.i += 1
            op = t.text
            if op == "&&":
                rhs = self.expression(prec + 1, live and lhs != 0, nesting)
                lhs = int(lhs != 0 and rhs != 0)
            elif op == "||":
                rhs = self.expression(prec + 1, live and lhs == 0, nesting)
                lhs = int(lhs != 0 or rhs != 0)
            else:
                rhs = self.expression(prec + 1, live, nesting)
                lhs = self._binary(op, lhs, rhs, t)

    def _binary(self, op: str, a: int, b: int, t: _Tok) -> int:
        if op in ("/", "%"):
            if b == 0:
                raise self._fail(f"division by zero in #{self.directive.text}", t)
            q = abs(a) // abs(b) * (1 if (a < 0) == (b < 0) else -1)
            return _wrap32(q if op == "/" else a - q * b)
        if op in ("<<", ">>"):
            b &= 31
            return _wrap32(a << b) if op == "<<" else a >> b
        return _wrap32({
            "*": lambda: a * b, "+": lambda: a + b, "-": lambda: a - b,
            "<": lambda: int(a < b), ">": lambda: int(a > b), "<=": lambda: int(a <= b),
            ">=": lambda: int(a >= b), "==": lambda: int(a == b), "!=": lambda: int(a != b),
            "&": lambda: a & b, "^": lambda: a ^ b, "|": lambda: a | b,
        }[op]())

    def unary(self, live: bool, nesting: int) -> int:
        if nesting > MAX_IF_NESTING:
            raise self._fail(f"the #{self.directive.text} expression is nested too deeply", self._peek())
        t = self._peek()
        if t is None:
            raise self._fail(f"the #{self.directive.text} expression ends too early", None)
        self.i += 1
        if t.kind == OP and t.text in ("+", "-", "~", "!"):
            v = self.unary(live, nesting + 1)
            return {"+": v, "-": _wrap32(-v), "~": _wrap32(~v), "!": int(v == 0)}[t.text]
        if t.kind == OP and t.text == "(":
            v = self.expression(1, live, nesting + 1)
            close = self._peek()
            if close is None or close.text != ")":
                raise self._fail("a ')' is missing in the #if expression", close)
            self.i += 1
            return v
        if t.kind == NUM:
            if not _INT_RE.fullmatch(t.text):
                raise self._fail(f"#if expressions use integers only; '{t.text}' is not an integer literal", t)
            v = int(t.text, 0) if not (t.text.startswith("0") and t.text[1:].isdigit()) else int(t.text, 8)
            if v > 0xFFFFFFFF:
                raise self._fail(f"the number '{t.text}' is too large for an #if expression", t)
            return _wrap32(v)
        if t.kind == ID:
            if live:
                raise self._fail(f"undefined macro '{t.text}' in #{self.directive.text}", t)
            return 0
        raise self._fail(f"unexpected '{t.text}' in the #{self.directive.text} expression", t)


def preprocess(units: list[Source], predefined: dict[str, str] | None = None, *, shadertoy: bool = True) -> PPResult:
    """Preprocess `units` in order (Shadertoy: Common, then the pass's tab) as one program.

    Raises GlslError at the first error, located in the user's file."""
    return _Preprocessor(predefined, shadertoy).run(units)
