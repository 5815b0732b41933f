"""Lexing: preprocessed GLSL text -> a list of `Token`s, as Lark's basic lexer would give them.

Owns the scanner the parser runs on, and the one lexical rule the grammar cannot say: an
IDENTIFIER that names a declared struct is a TYPE_NAME (the spec's TYPE_NAME token, section 9),
and a word reserved for future use (3.8), or longer than 1024 characters (3.8), cannot be a name.

The struct-name rule is scope-aware, as C lexers track typedef names: a variable or parameter
may reuse a struct's name in an inner scope (spec 4.2.2-4.2.3: the inner name hides the type),
as in `bool hit(in sphere sphere) { return sphere.radius > 0.0; }`. A struct name right after a
type (`sphere sphere`: two types are never adjacent) is the declared name, an IDENTIFIER, and
the type name stays hidden until that scope closes: the block's `}` for a local, the function
body's `}` (or the prototype's `;`) for a parameter.

The terminals, their regular expressions, priorities and names all come from the grammar, as
Lark loads it (grammar/glsl.lark); `lexer_tables` arranges them for speed ahead of time
(frontend/parse_tables.py ships the result, so Lark is not imported at run time):

* one master regular expression, its alternatives in the order Lark's basic lexer tries them
  (priority, then longest possible match, then name), so the same text gives the same
  terminal: floats before integers, `<<=` before `<<` before `<`;
* keywords are not alternatives of their own: a word is matched as an IDENTIFIER and then
  looked up in a dict of the grammar's keyword strings, which is what Lark does too;
  likewise each run of operator strings is one alternative, the match looked up by its text;
* ignored white space is skipped by the same match, before the token;
* the tokens are built directly, with the same type, value, positions, lines and columns (a
  token's line and columns are computed when first read: only tests and error messages read
  them, and tracking lines cost a sixth of the lexer's time).

The whole text is lexed before parsing. An error (an unexpected character, a reserved word
used as a name) is not raised at once but kept in `Tokens.error`: the parser raises it when it
reaches that point, so an earlier syntax error is still the one reported, as with Lark's lazy
lexer.

Tested against Lark's own lexer on the corpus, the lab shaders and mutations of them
(tests/parse/test_fast_parser.py).
"""

from __future__ import annotations

import re
from bisect import bisect_right

from ..base.records import record
from ..base.regexes import compiled
from ..language.builtin_functions import RESERVED_WORDS
from ..language.glsl_types import BY_NAME

_TYPE_WORDS = frozenset(BY_NAME)  # a word after one of these (or a TYPE_NAME) is a declared name

IDENTIFIER = "IDENTIFIER"
TYPE_NAME = "TYPE_NAME"
STRUCT = "STRUCT"
ERROR_KIND = "_unexpected"  # the master regex's group for a character no terminal matches


class Token(str):
    """A token: its text, with the same attributes as Lark's Token (the parse tree's leaves).

    The lexer gives a token its text, type and offsets; its lines and columns (read only by
    tests and a few error messages) are computed from the text's line starts when first read."""

    __slots__ = ("type", "value", "start_pos", "end_pos", "_where", "_lines")
    type: str
    value: str
    start_pos: int | None
    end_pos: int | None
    _where: tuple[int | None, int | None, int | None, int | None]
    _lines: _Lines

    def __new__(
        cls,
        type: str,
        value: str,
        start_pos: int | None = None,
        line: int | None = None,
        column: int | None = None,
        end_line: int | None = None,
        end_column: int | None = None,
        end_pos: int | None = None,
    ):
        tok = str.__new__(cls, value)
        tok.type = type
        tok.value = value
        tok.start_pos = start_pos
        tok.end_pos = end_pos
        tok._where = (line, column, end_line, end_column)
        return tok

    @classmethod
    def new_borrow_pos(cls, type: str, value: str, borrow: Token) -> Token:
        return cls(
            type,
            value,
            borrow.start_pos,
            borrow.line,
            borrow.column,
            borrow.end_line,
            borrow.end_column,
            borrow.end_pos,
        )

    def _position(self) -> tuple:
        """(line, column, end_line, end_column), computed once from the lexed text's lines."""
        try:
            return self._where
        except AttributeError:  # a token the lexer made: it has its offsets and lines
            assert self.start_pos is not None and self.end_pos is not None
            where = self._where = self._lines.where(self.start_pos, self.end_pos)
            return where

    line = property(lambda self: self._position()[0])
    column = property(lambda self: self._position()[1])
    end_line = property(lambda self: self._position()[2])
    end_column = property(lambda self: self._position()[3])

    def __repr__(self) -> str:
        return f"Token({self.type!r}, {self.value!r})"


class _Lines:
    """The line starts of a lexed text, found when a token's line is first read."""

    __slots__ = ("text", "starts")

    def __init__(self, text: str) -> None:
        self.text = text
        self.starts: list[int] | None = None

    def where(self, start: int, end: int) -> tuple[int, int, int, int]:
        starts = self.starts
        if starts is None:
            starts = self.starts = [0]
            find = self.text.find
            at = find("\n")
            while at >= 0:
                starts.append(at + 1)
                at = find("\n", at + 1)
        line = bisect_right(starts, start)
        end_line = bisect_right(starts, end)
        return line, start - starts[line - 1] + 1, end_line, end - starts[end_line - 1] + 1


class UnexpectedInput(Exception):
    """A syntax error the lexer or the parser met (frontend/parser.py words it for the user)."""


class UnexpectedCharacters(UnexpectedInput):
    """A character no terminal matches, at `pos_in_stream` (line and column from 1)."""

    def __init__(
        self, text: str, pos_in_stream: int, line: int, column: int, allowed: frozenset[str]
    ) -> None:
        super().__init__(
            f"unexpected character {text[pos_in_stream : pos_in_stream + 1]!r} at line {line}, "
            f"column {column}"
        )
        self.pos_in_stream = pos_in_stream
        self.line = line
        self.column = column
        self.allowed = allowed


# The syntax error messages look back at the last tokens the parser saw (to name the
# statement, to find the previous token). They have always seen a window of 33 to 64 tokens:
# the post-lexer that kept them dropped the oldest 32 past 64. `Tokens.history` gives the same
# window, so no message changes.
_HISTORY_MAX = 64
_HISTORY_DROP = 32

_new_str = str.__new__


# GLSL ES 3.00 section 3.8: "The maximum length of an identifier is 1024 characters." (Mesa
# rejects a longer one: "Identifier `...' exceeds 1024 characters".)
MAX_IDENTIFIER_LENGTH = 1024


class BadNameError(Exception):
    """A word that cannot be a name; `token` is where, `message` and `help` say why."""

    def __init__(self, token: Token, message: str, help: str | None = None) -> None:
        super().__init__(message)
        self.token, self.message, self.help = token, message, help


class ReservedWordError(BadNameError):
    """A reserved word (GLSL ES 3.00 section 3.8) used as a name."""

    def __init__(self, token: Token) -> None:
        value = token.value
        super().__init__(
            token,
            f"'{value}' is a reserved word in GLSL ES 3.00 and cannot be used as a name",
            f"rename it, for example to '{value}_'",
        )


class LongIdentifierError(BadNameError):
    """An identifier longer than MAX_IDENTIFIER_LENGTH characters."""

    def __init__(self, token: Token) -> None:
        super().__init__(
            token,
            f"an identifier of {len(token.value)} characters; GLSL ES 3.00 allows at most "
            f"{MAX_IDENTIFIER_LENGTH} (section 3.8)",
            "use a shorter name",
        )


@record(slots=False)
class Tokens:
    """The tokens of a text and the error that stopped the lexer, if any (raised by the parser
    when it has consumed every token before it)."""

    text: str
    tokens: list[Token]
    error: Exception | None

    def history(self, count: int) -> list[Token]:
        """The window of last tokens the error messages see after the parser saw `count`."""
        if count > _HISTORY_MAX:
            kept = _HISTORY_MAX - _HISTORY_DROP + 1 + (count - _HISTORY_MAX - 1) % _HISTORY_DROP
        else:
            kept = count
        return self.tokens[count - kept : count]

    def open_brackets(self, count: int) -> list[Token]:
        """The brackets still open after the first `count` tokens, outermost first."""
        stack: list[Token] = []
        for tok in self.tokens[:count]:
            v = tok.value
            if v in ("{", "(", "["):
                stack.append(tok)
            elif v in ("}", ")", "]") and stack:
                stack.pop()
        return stack

    def count_through(self, tok: Token) -> int:
        """How many tokens the parser had seen when it failed on `tok` (all of them at the end)."""
        for i in range(len(self.tokens) - 1, -1, -1):
            if self.tokens[i] is tok:
                return i + 1
        return len(self.tokens)


def lexer_tables(lexer_conf) -> dict:
    """The scanner's tables for a grammar Lark loaded (`lark.lexer_conf`), as JSON-ready data
    (frontend/parse_tables.py builds them ahead of time; `Lexer` runs them)."""
    terminals = list(lexer_conf.terminals)
    flags = lexer_conf.g_regex_flags
    ignore = frozenset(lexer_conf.ignore)
    # Lark's basic lexer tries terminals in this order; the first alternative that matches wins.
    terminals.sort(key=lambda t: (-t.priority, -t.pattern.max_width, -len(t.pattern.value), t.name))
    # A string terminal that a regex terminal of the same priority matches in full (a
    # keyword and IDENTIFIER) is found by looking the regex's match up, not by scanning.
    keywords: dict[str, dict[str, str]] = {}
    embedded = set()
    for retok in terminals:
        if retok.pattern.type != "re":
            continue
        words: dict[str, str] = {}
        for strtok in terminals:
            if strtok.pattern.type != "str" or strtok.priority != retok.priority:
                continue
            word = strtok.pattern.value
            m = re.match(retok.pattern.to_regexp(), word, flags)
            if m and m.group(0) == word:
                words.setdefault(word, strtok.name)
                if strtok.pattern.flags <= retok.pattern.flags:
                    embedded.add(strtok.name)
        if words:
            keywords[retok.name] = words
    if set(keywords) - {IDENTIFIER}:
        raise ValueError(
            f"only IDENTIFIER may contain keywords, not {sorted(set(keywords) - {IDENTIFIER})}"
        )
    scanned = [t for t in terminals if t.name not in embedded]
    # The ignored terminals (white space) are skipped before each token. They start with
    # characters no other terminal starts with, so trying them first changes nothing (a
    # property of this grammar, which tests/parse/test_fast_parser.py checks against Lark).
    skip = "|".join(t.pattern.to_regexp() for t in scanned if t.name in ignore)
    prefix = f"(?:{skip})*" if skip else ""
    one_class = re.fullmatch(r"\(\?:(\[[^\]]*\])\)\+", skip)
    if one_class:  # `(?:(?:[ \t\n])+)*` is `[ \t\n]*`, without the regex engine's nested repeat
        prefix = one_class.group(1) + "*"
    # Each run of consecutive string terminals (the operators) is one alternative, its
    # strings in the same order, and the match is looked up: one named group per operator
    # would make the regex engine do group bookkeeping for each alternative it tries.
    literals: dict[str, dict[str, str]] = {}
    multiline_literals = False
    parts: list[str] = []
    run: list = []
    for t in [t for t in scanned if t.name not in ignore] + [None]:
        if t is not None and t.pattern.type == "str":
            run.append(t)
            continue
        if run:
            group = f"_literal{len(literals)}"
            names: dict[str, str] = {}
            for lit in run:
                names.setdefault(lit.pattern.value, lit.name)
                multiline_literals |= "\n" in lit.pattern.value
            literals[group] = names
            parts.append(f"(?P<{group}>{'|'.join(lit.pattern.to_regexp() for lit in run)})")
            run = []
        if t is not None:
            parts.append(f"(?P<{t.name}>{t.pattern.to_regexp()})")
    # After the last token only ignored text may remain (`\Z`); any other character that
    # no terminal matches is the lexer error.
    return {
        "pattern": f"{prefix}(?:{'|'.join(parts)}|(?P<{ERROR_KIND}>[\\s\\S])|\\Z)",
        "flags": int(flags),
        "keywords": keywords,
        "literals": literals,
        "multiline_literals": multiline_literals,
        "allowed": sorted({t.name for t in scanned} - ignore),
    }


class Lexer:
    """The scanner for one grammar, from its tables (`lexer_tables`; build it once per process)."""

    def __init__(self, tables: dict) -> None:
        self.keywords: dict[str, dict[str, str]] = tables["keywords"]
        self.literals: dict[str, dict[str, str]] = tables["literals"]
        self.multiline_literals: bool = tables["multiline_literals"]
        self.allowed = frozenset(tables["allowed"])
        self.error_kind = ERROR_KIND
        self.master = compiled(tables["pattern"], tables["flags"])

    def tokenize(self, text: str) -> Tokens:
        """Every token of `text`; an error stops the lexer and is kept in `Tokens.error`."""
        tokens: list[Token] = []
        append = tokens.append
        keywords = self.keywords.get(IDENTIFIER, {})
        literals = self.literals
        error_kind = self.error_kind
        reserved = RESERVED_WORDS
        lines = _Lines(text)
        struct_names: set[str] = set()
        after_struct = False
        # scopes: a struct name hidden by a variable or parameter of that name, and the brace
        # depth at which it shows again (a parameter's: its function's depth, after the body)
        depth = parens = 0
        hidden: list[tuple[str, int, bool]] = []  # (name, depth it shows again at, parameter)
        prev_type = False  # the previous token is a type: a struct name now is a declared name
        prev_dot = False  # the previous token is '.': a name now selects a field, never a type
        error: Exception | None = None
        for m in self.master.finditer(text):
            kind = m.lastgroup
            if kind is None:  # only ignored text was left
                break
            start, end = m.span(kind)
            value = text[start:end]
            if kind == IDENTIFIER:
                word_kind = keywords.get(value)
                if word_kind is not None:
                    kind = word_kind
                    after_struct = word_kind == STRUCT
                else:
                    # The struct-name rule: a name right after `struct` declares a type name.
                    if after_struct:
                        struct_names.add(value)
                        after_struct = False
                    elif value in struct_names and not prev_dot:
                        if prev_type and (depth > 0 or parens > 0):
                            struct_names.discard(value)  # `sphere sphere`: hides the type
                            hidden.append((value, depth if parens else depth - 1, parens > 0))
                        else:
                            kind = TYPE_NAME
                    if value in reserved:
                        error = ReservedWordError(self._token(kind, value, start, end, text))
                        break
                    if len(value) > MAX_IDENTIFIER_LENGTH:
                        error = LongIdentifierError(self._token(kind, value, start, end, text))
                        break
            else:
                after_struct = False
                names = literals.get(kind)
                if names is not None:
                    kind = names[value]
                    if hidden or value in "{}();":
                        depth, parens = self._scope(value, depth, parens, hidden, struct_names)
                elif kind == error_kind:
                    tok = self._token(kind, value, start, end, text)
                    error = UnexpectedCharacters(text, start, tok.line, tok.column, self.allowed)
                    break
            prev_type = kind == TYPE_NAME or value in _TYPE_WORDS
            prev_dot = value == "."
            tok = _new_str(Token, value)
            tok.type = kind
            tok.value = value
            tok.start_pos = start
            tok.end_pos = end
            tok._lines = lines
            append(tok)
        return Tokens(text, tokens, error)

    @staticmethod
    def _scope(
        value: str, depth: int, parens: int, hidden: list, struct_names: set[str]
    ) -> tuple[int, int]:
        """Brace and parenthesis depth after the punctuation `value`; a struct name hidden in a
        scope that closes here is a type name again."""
        if value == "{":
            depth += 1
        elif value == "}":
            depth -= 1
        elif value == "(":
            parens += 1
        elif value == ")":
            parens = max(parens - 1, 0)
        if value in "};" and parens == 0:
            while hidden:
                name, show, parameter = hidden[-1]
                if not (
                    (value == "}" and depth <= show)
                    or (value == ";" and parameter and depth == show)
                ):
                    break
                struct_names.add(name)
                hidden.pop()
        return depth, parens

    @staticmethod
    def _token(kind: str, value: str, start: int, end: int, text: str) -> Token:
        tok = _new_str(Token, value)
        tok.type = kind
        tok.value = value
        tok.start_pos = start
        tok.end_pos = end
        tok._lines = _Lines(text)
        return tok
