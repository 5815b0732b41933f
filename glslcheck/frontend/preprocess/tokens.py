"""Preprocessing tokens: what the preprocessor reads a line as (identifiers, numbers, operators,
any other character), each with its offsets in the unit's stripped text.
"""

from __future__ import annotations

import re

from ...base.regexes import compiled

ID, NUM, OP, OTHER = "id", "num", "op", "other"

_NUMBER = (
    r"(?:0[xX][0-9A-Fa-f]*|(?:[0-9]+\.[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|[0-9]+(?:[eE][+-]?[0-9]+)?)"
    r"[A-Za-z0-9_]*"
)
_OPERATOR = (
    r"<<=|>>=|\+\+|--|<<|>>|<=|>=|==|!=|&&|\|\||\^\^|\+=|-=|\*=|/=|%=|&=|\^=|\|=|\#\#"
    r"|[-+*/%<>=!~&|^?:;,.()\[\]{}\#]"
)
WS = " \t\n\v\f\r"
_TOKEN_RE = compiled(
    rf"[{WS}]*(?:(?P<id>[A-Za-z_][A-Za-z0-9_]*)|(?P<num>{_NUMBER})|(?P<op>{_OPERATOR})|(?P<other>[^{WS}]))",
    re.S,
)


class Token:
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


def lex(text: str, pos: int, end: int) -> Token | None:
    """The next token of `text[pos:end]`, or None at the end."""
    m = _TOKEN_RE.match(text, pos, end)
    if m is None:
        return None
    kind = m.lastgroup
    assert kind is not None  # every alternative of the pattern is a named group
    t = m.group(kind)
    e = m.end()
    s = e - len(t)
    return Token(kind, t, s, e, s > pos)


def lex_all(text: str, pos: int, end: int) -> list[Token]:
    out: list[Token] = []
    while True:
        t = lex(text, pos, end)
        if t is None:
            return out
        out.append(t)
        pos = t.end
