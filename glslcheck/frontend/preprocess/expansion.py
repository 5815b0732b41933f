"""Macro expansion as in C, without `#` and `##` (GLSL ES has neither): arguments are expanded
before they are substituted, the result is rescanned, and a macro is never expanded inside its own
expansion (each token carries the set of macros it must not be expanded by again). Runaway macros
stop at MAX_EXPANSION_DEPTH nested expansions or MAX_EXPANSION_TOKENS tokens produced.
"""

from __future__ import annotations

from heapq import heapify, heappop, heappush

from ...base.diagnostics import GlslError
from .context import MAX_EXPANSION_DEPTH, MAX_EXPANSION_TOKENS, PreprocessorState
from .tokens import ID, NUM, OP, WS, Token, lex
from .units import Unit

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

_EMPTY: frozenset[str] = frozenset()


class TokenInput:
    """Tokens to expand: a stack of pushed-back tokens, then (at the top level) the file."""

    __slots__ = ("stack", "text", "pos", "end", "src_end", "peeked")

    def __init__(self, tokens: list[Token], text: str = "", pos: int = 0, end: int = 0):
        self.stack = tokens[::-1]
        self.text = text
        self.pos = pos
        self.end = end
        self.src_end = pos  # end of the last token consumed from the file
        self.peeked: Token | None = None

    def next(self) -> Token | None:
        if self.stack:
            return self.stack.pop()
        t = self.peeked or lex(self.text, self.pos, self.end)
        self.peeked = None
        if t is not None:
            self.pos = self.src_end = t.end
        return t

    def peek_lparen(self) -> bool:
        if self.stack:
            return self.stack[-1].text == "("
        if self.peeked is None:
            self.peeked = lex(self.text, self.pos, self.end)
        return self.peeked is not None and self.peeked.text == "("


def expand_text_run(pp: PreprocessorState, u: Unit, a: int, b: int) -> None:
    """Expand the macros of active text lines [a, b) and write them out."""
    text = u.stripped
    macros = pp.macros
    pos = a
    for s, name in _macro_names_at(text, macros, a, b):
        if s < pos:
            continue
        macro = macros[name]
        if _inside_number(text, s):
            continue
        e = s + len(name)
        inp = TokenInput([], text, e, b)
        if macro.params is not None and not inp.peek_lparen():
            continue
        out: list[Token] = []
        expand_token(pp, Token(ID, name, s, e), inp, out, 0)
        while inp.stack:
            expand_token(pp, inp.stack.pop(), inp, out, 0)
        use_end = inp.src_end
        pp.emit_verbatim(u, pos, s)
        lead = "" if s == a or text[s - 1] in WS else " "
        trail = "" if text[use_end] in WS else " "
        pp.emit(lead + " ".join(t.text for t in out) + trail, u, s, use_end)
        pos = use_end
    pp.emit_verbatim(u, pos, b)


def expand_list(pp: PreprocessorState, tokens: list[Token], depth: int) -> list[Token]:
    """Fully macro-expand a token list on its own (a macro argument, an #if line)."""
    if depth > MAX_EXPANSION_DEPTH:
        t = tokens[0] if tokens else None
        raise expansion_error(pp, "deep", t)
    inp = TokenInput(tokens)
    out: list[Token] = []
    while inp.stack:
        expand_token(pp, inp.stack.pop(), inp, out, depth)
    return out


def expansion_error(pp: PreprocessorState, what: str, t: Token | None) -> GlslError:
    s, e = t.span() if t is not None else (0, 0)
    return pp.error(
        f"macro expansion is too {'deep' if what == 'deep' else 'large'}"
        + (
            f" (more than {MAX_EXPANSION_DEPTH} nested expansions)"
            if what == "deep"
            else f" (more than {MAX_EXPANSION_TOKENS} tokens)"
        ),
        s,
        e,
        help="a macro probably expands to itself through other macros, or doubles at each level",
    )


def expand_token(
    pp: PreprocessorState, t: Token, inp: TokenInput, out: list[Token], depth: int
) -> None:
    """Expand t if it names a macro (pushing the result back onto inp), else output it."""
    name = t.text
    macro = pp.macros.get(name) if t.kind == ID else None
    if macro is None or (t.hide is not None and name in t.hide):
        out.append(t)
        return
    hide = t.hide or _EMPTY
    if macro.params is None:
        use = t.span()
        body = macro.tokens
        if macro.dynamic:
            line = pp.unit.line_of(use[0]) + pp.line_delta
            value = line if name == "__LINE__" else pp.file_number
            body = [Token(NUM, str(value), 0, 0)]
    else:
        if not inp.peek_lparen():
            out.append(t)
            return
        inp.next()
        args, rp = _collect_args(pp, t, inp)
        nparams = len(macro.params)
        if nparams == 0 and args == [[]]:
            args = []
        if len(args) != nparams:
            s, e = t.span()[0], rp.span()[1]
            raise pp.error(
                f"macro '{name}' takes {nparams} argument{'s' if nparams != 1 else ''} "
                f"but {len(args)} {'were' if len(args) != 1 else 'was'} given",
                s,
                e,
                help=f"'{name}' is defined at {macro.loc}" if macro.loc else None,
            )
        hide = hide & (rp.hide or _EMPTY)
        use = (t.span()[0], rp.span()[1])
        index = {p: i for i, p in enumerate(macro.params)}
        expanded: dict[int, list[Token]] = {}
        body = []
        for b in macro.tokens:
            i = index.get(b.text) if b.kind == ID else None
            if i is None:
                body.append(b)
            else:
                if i not in expanded:
                    expanded[i] = expand_list(pp, args[i], depth + 1)
                body.extend(expanded[i])
    key = (hide, name)
    new_hide = pp.hide_cache.get(key)
    if new_hide is None:
        new_hide = pp.hide_cache[key] = hide | {name}
        if len(new_hide) > MAX_EXPANSION_DEPTH:
            raise expansion_error(pp, "deep", t)
    hide = new_hide
    pp.budget -= len(body)
    if pp.budget < 0:
        raise expansion_error(pp, "large", t)
    stack = inp.stack
    for b in reversed(body):
        stack.append(
            Token(
                b.kind,
                b.text,
                use[0],
                use[1],
                b.ws,
                hide if b.hide is None else (b.hide | hide),
                use,
            )
        )


def _collect_args(
    pp: PreprocessorState, name: Token, inp: TokenInput
) -> tuple[list[list[Token]], Token]:
    args: list[list[Token]] = [[]]
    level = 0
    while True:
        t = inp.next()
        if t is None:
            raise pp.token_error(
                f"the argument list of macro '{name.text}' is not closed: a ')' is missing",
                name,
                help="a macro call in a directive must end on the same line"
                if inp.end == 0
                else None,
            )
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
        if (i == 0 or text[i - 1] not in _WORD_CHARS) and (
            i + n == end or text[i + n] not in _WORD_CHARS
        ):
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
