"""The fast lexer (glslcheck/frontend/lexer.py) and LALR driver (glslcheck/frontend/lalr.py) against
Lark itself.

The reference is Lark's own basic lexer and LALR parser on the same grammar and tables, with
`_Reference` as its post-lexer: the struct-name and reserved-word rule written the plain way
(a generator over Lark's lazy token stream, as frontend/parser.py had it before frontend/lexer.py
took over). On every corpus shader, every lab program and seeded mutations of each (tokens deleted,
duplicated, swapped, replaced, glued together or split, stray characters inserted), both
sides must give the same tokens (type, text, positions, lines, columns), the same tree, or
the same error at the same token with the same expected terminals, and the same history and
open brackets for the error message.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
from lark import Lark, Token
from lark import Tree as LarkTree
from lark import exceptions as lark_exceptions
from lark.lark import PostLex

from glslcheck.frontend.lalr import Tree, UnexpectedToken
from glslcheck.frontend.lexer import ReservedWordError, UnexpectedCharacters
from glslcheck.frontend.parse_tables import LARK_OPTIONS
from glslcheck.frontend.parser import get_parser, grammar_text
from glslcheck.frontend.preprocess import preprocess
from glslcheck.language.builtin_functions import RESERVED_WORDS
from glslcheck.language.glsl_types import BY_NAME
from glslcheck.shadertoy.sources import find_shaders

ROOT = Path(__file__).resolve().parents[2]
SOURCES = sorted(p for p in (ROOT / "tests" / "corpus").iterdir() if p.is_file()) + sorted(
    p for p in (ROOT / "lab_shaders").glob("*") if p.is_dir()
)
MUTATIONS_PER_PROGRAM = 20


class _Reserved(Exception):
    def __init__(self, tok: Token) -> None:
        self.tok = tok


class _Reference(PostLex):
    """IDENTIFIER -> TYPE_NAME after `struct S`, reserved words rejected, history kept.

    Scopes: a struct name declared as a variable or parameter (`S S`, right after a type)
    is an IDENTIFIER, and not a type name until its scope closes (`}` of its block, or of its
    function's body for a parameter, or a prototype's `;`)."""

    def reset(self) -> None:
        self.struct_names: set[str] = set()
        self.open_brackets: list[Token] = []
        self.history: list[Token] = []

    def process(self, stream):
        after_struct = False
        after_type = False
        after_dot = False
        braces = parens = 0
        hiding: list[tuple[str, int, bool]] = []  # (name, braces when it shows again, parameter)
        for tok in stream:
            if tok.type == "IDENTIFIER":
                if after_struct:
                    self.struct_names.add(tok.value)
                elif after_dot:  # a field's name, never a type
                    pass
                elif tok.value in self.struct_names and after_type and (braces or parens):
                    self.struct_names.remove(tok.value)
                    hiding.append((tok.value, braces if parens else braces - 1, parens > 0))
                elif tok.value in self.struct_names:
                    tok = Token.new_borrow_pos("TYPE_NAME", tok.value, tok)
                if tok.value in RESERVED_WORDS:
                    raise _Reserved(tok)
            after_struct = tok.type == "STRUCT"
            after_dot = tok.value == "."
            after_type = tok.type == "TYPE_NAME" or tok.value in BY_NAME
            braces += {"{": 1, "}": -1}.get(tok.value, 0)
            parens = max(parens + {"(": 1, ")": -1}.get(tok.value, 0), 0)
            for name, shows, parameter in reversed(list(hiding)):
                if parens or not (
                    (tok.value == "}" and braces <= shows)
                    or (tok.value == ";" and parameter and braces == shows)
                ):
                    break
                self.struct_names.add(name)
                hiding.pop()
            if tok.value in ("{", "(", "["):
                self.open_brackets.append(tok)
            elif tok.value in ("}", ")", "]") and self.open_brackets:
                self.open_brackets.pop()
            self.history.append(tok)
            if len(self.history) > 64:
                del self.history[:32]
            yield tok


@pytest.fixture(scope="module")
def reference():
    post = _Reference()
    return Lark(grammar_text(), **LARK_OPTIONS, postlex=post), post


def _texts(source: Path) -> list[str]:
    out = []
    for shader in find_shaders([str(source)]):
        for tab in [t for t in shader.tabs if t != "Common"] or ["Common"]:
            units = shader.units_for(tab)
            out.append(preprocess(units, shadertoy=not units[-1].is_plain_glsl).text)
    return out


_REPLACEMENTS = [
    "input",
    "struct",
    "S",
    "float",
    "vec3",
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    ";",
    ",",
    ".",
    "=",
    "<<=",
    ">>",
    "++",
    "?",
    ":",
    "1.",
    ".5e3",
    "0x1Fu",
    "09",
    "1e5",
    "1.0f",
    "3u",
    "true",
    "else",
    "if",
    "return",
    "void",
    "TYPE",
]
_STRAYS = ["@", "$", '"', "'", "#", "\\", "\x00", "\u00e9", "\x0b", "`"]


def _mutate(text: str, spans: list[tuple[int, int]], rng: random.Random) -> str:
    """One random edit at a token of `text` (`spans` are the tokens' start and end)."""
    start, end = spans[rng.randrange(len(spans))]
    kind = rng.randrange(9)
    if kind == 0:  # delete the token
        return text[:start] + text[end:]
    if kind == 1:  # duplicate it
        return text[:end] + " " + text[start:end] + text[end:]
    if kind == 2:  # replace it
        return text[:start] + rng.choice(_REPLACEMENTS) + text[end:]
    if kind == 3:  # a stray character before it
        return text[:start] + rng.choice(_STRAYS) + text[start:]
    if kind == 4:  # glue it to the next token
        rest = text[end:]
        return text[:end] + rest.lstrip(" \t\r\n\f")
    if kind == 5 and end - start > 1:  # split it
        cut = rng.randrange(start + 1, end)
        return text[:cut] + rng.choice([" ", "\n"]) + text[cut:]
    if kind == 6:  # swap with the next token
        i = spans.index((start, end))
        if i + 1 < len(spans):
            s2, e2 = spans[i + 1]
            return text[:start] + text[s2:e2] + text[end:s2] + text[start:end] + text[e2:]
    if kind == 7 and text[start].isalpha():  # a name becomes a reserved word
        return text[:start] + rng.choice(sorted(RESERVED_WORDS)) + text[end:]
    return text[:start] + "struct S { float x; } s;\nS " + text[start:]  # a struct name in use


def _cases(source: Path) -> list[str]:
    lexer = get_parser().lexer
    rng = random.Random(source.name)
    cases = []
    for text in _texts(source):
        cases.append(text)
        spans = [(t.start_pos, t.end_pos) for t in lexer.tokenize(text).tokens]
        for _ in range(MUTATIONS_PER_PROGRAM):
            cases.append(_mutate(text, spans, rng))
    return cases


def _tok(t: Token) -> tuple:
    return (t.type, t.value, t.start_pos, t.end_pos, t.line, t.column, t.end_line, t.end_column)


def _tree(item):
    """A tree as nested tuples: Lark's (the reference) and frontend/lalr.py's alike."""
    if isinstance(item, (Tree, LarkTree)):
        return (item.data, tuple(_tree(c) for c in item.children))
    return _tok(item) if isinstance(item, str) else item


def _reference_tokens(reference, text: str):
    lark, post = reference
    post.reset()
    out = []
    try:
        for tok in lark.lex(text):
            out.append(_tok(tok))
    except lark_exceptions.UnexpectedCharacters as e:
        return out, ("character", e.pos_in_stream, e.line, e.column)
    except _Reserved as e:
        return out, ("reserved", _tok(e.tok))
    return out, None


def _our_tokens(text: str):
    lexed = get_parser().lexer.tokenize(text)
    error = lexed.error
    if isinstance(error, UnexpectedCharacters):
        error = ("character", error.pos_in_stream, error.line, error.column)
    elif isinstance(error, ReservedWordError):
        error = ("reserved", _tok(error.token))
    return [_tok(t) for t in lexed.tokens], error


def _reference_parse(reference, text: str):
    lark, post = reference
    post.reset()
    try:
        return ("tree", _tree(lark.parse(text)))
    except lark_exceptions.UnexpectedToken as e:
        return (
            "token",
            _tok(e.token),
            sorted(e.expected),
            [_tok(t) for t in post.history],
            [_tok(t) for t in post.open_brackets],
        )
    except lark_exceptions.UnexpectedCharacters as e:
        return (
            "character",
            e.pos_in_stream,
            [_tok(t) for t in post.history],
            [_tok(t) for t in post.open_brackets],
        )
    except _Reserved as e:
        return ("reserved", _tok(e.tok))


def _our_parse(text: str):
    parser = get_parser()
    lexed = parser.lexer.tokenize(text)
    try:
        return ("tree", _tree(parser.driver.parse(lexed)))
    except UnexpectedToken as e:
        seen = lexed.count_through(e.token)
        return (
            "token",
            _tok(e.token),
            sorted(e.expected),
            [_tok(t) for t in lexed.history(seen)],
            [_tok(t) for t in lexed.open_brackets(seen)],
        )
    except UnexpectedCharacters as e:
        seen = len(lexed.tokens)
        return (
            "character",
            e.pos_in_stream,
            [_tok(t) for t in lexed.history(seen)],
            [_tok(t) for t in lexed.open_brackets(seen)],
        )
    except ReservedWordError as e:
        return ("reserved", _tok(e.token))


@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.name)
def test_tokens_and_trees_match_lark(reference, source):
    outcomes = set()
    for text in _cases(source):
        assert _our_tokens(text) == _reference_tokens(reference, text), repr(text)
        ours = _our_parse(text)
        assert ours == _reference_parse(reference, text), repr(text)
        outcomes.add(ours[0])
    assert "tree" in outcomes  # the unmutated program parses


def test_mutations_reach_every_outcome(reference):
    """The mutations exercise every path: trees, syntax errors, lexer errors, reserved words."""
    outcomes = set()
    for source in SOURCES:
        for text in _cases(source):
            outcomes.add(_our_parse(text)[0])
    assert outcomes == {"tree", "token", "character", "reserved"}


@pytest.mark.parametrize(
    "text",
    [
        "",
        "   \n\t ",
        "float x;",
        "float x;\n\n   ",
        "float x = 1.;\nfloat y = .5e-3; uint z = 0xFFu; int w = 077;",
        "struct S { float a; }; S s; S[2] t; float f() { return S(1.0).a; }",
        "struct S { float S; }; struct L { S L[2]; }; float f(L l) { return l.L[0].S; }",
        "float a = b<<=c>>=d<=e>=f==g!=h&&i||j^^k++--l;",
        "int x = 1\x0b;",
        "float\x00 x;",
        "float x; @",
        "float input;",
        "float x = 1.0e;",
        "float x = (1.0;",
        "void main() {",
        "void main() { if (x) }",
    ],
)
def test_small_texts_match_lark(reference, text):
    assert _our_tokens(text) == _reference_tokens(reference, text)
    assert _our_parse(text) == _reference_parse(reference, text)


def test_history_window_matches_lark_over_long_programs(reference):
    """The error-message history keeps Lark's post-lexer window (33 to 64 tokens) at any length."""
    body = "".join(f"float v{i} = {i}.0;\n" for i in range(60))
    for cut in (";", "x x"):
        text = body + cut + "\n" + body
        assert _our_parse(text) == _reference_parse(reference, text)
    for n in range(60, 140, 7):
        text = "float a = " + " + ".join(["1.0"] * n) + " +;"
        assert _our_parse(text) == _reference_parse(reference, text)
