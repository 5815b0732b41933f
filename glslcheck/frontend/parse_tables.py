"""The parser's tables: built from grammar/glsl.lark by Lark, shipped as a generated module, loaded
at start-up.

Owns the one step that needs Lark: turning the grammar into what frontend/lexer.py and
frontend/lalr.py run on (the lexer's master regular expression and keyword tables, the LALR action
table, and for each rule the shape of the tree it builds). Lark does that analysis in about a
second, so it is done ahead of time and the result ships in the package as
`glslcheck/grammar/glsl_tables.py`: a module of plain literals (tuples, strings, bytes, numbers;
tests/robustness checks that it holds nothing else), never a pickle, and never written at run time,
so no cache file exists that another user could plant and a CLI call does not import Lark. As a
module it is read from its `.pyc` like the rest of the package: its literals are the code's
constants, which the interpreter unmarshals in C, far cheaper at start-up than parsing a JSON file
into lists (docs/performance.md).

The module records the SHA-256 of the grammar it was built from. `load()` compares it with the
grammar that ships beside it; stale tables (the grammar was edited and the tables were not
rebuilt) are not used: the tables are built in memory from the grammar, with a warning, and
nothing is written. Rebuild the module after editing the grammar with

    python -m glslcheck.frontend.parse_tables

tests/parse/test_parse_tables.py checks that the shipped module is the one this module builds
from the shipped grammar, and that stale or damaged tables are detected.
"""

from __future__ import annotations

import os
import sys

from ..base.generated import write_generated

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

TABLES_MODULE = "glsl_tables"  # glslcheck/grammar/glsl_tables.py
TABLES_FILE = TABLES_MODULE + ".py"
GRAMMAR_FILE = "glsl.lark"
FORMAT = 4  # bump when the layout of the module changes (2: the JSON file)

# The Lark options the tables are built with (Lark is only used here, ahead of time).
LARK_OPTIONS = dict(
    parser="lalr",
    # Lark's basic lexer, not the contextual one, is the lexer frontend/lexer.py reproduces: a
    # contextual lexer would read `float` as a name where only a name can follow
    # (`float float;`), hiding the keyword.
    lexer="basic",
    strict=True,
    # Positions come from the tokens (see parse._Builder.loc); keeping every token gives
    # exact spans that include keywords and braces.
    propagate_positions=False,
    keep_all_tokens=True,
    maybe_placeholders=True,
)

# Words a user might mean: what each terminal is called in an error message.
_TOKEN_WORDS = {
    "IDENTIFIER": "a name",
    "TYPE_NAME": "a type name",
    "INTCONSTANT": "a number",
    "FLOATCONSTANT": "a number",
    "$END": "the end of the file",
}


class StaleTablesError(Exception):
    """The tables file was not built from the grammar beside it."""


def grammar_folder() -> str:
    """The folder of the installed grammar package (grammar/ ships as glslcheck.grammar)."""
    from .. import grammar

    return os.path.dirname(grammar.__file__)


def grammar_text() -> str:
    with open(os.path.join(grammar_folder(), GRAMMAR_FILE), encoding="utf-8") as f:
        return f.read()


def grammar_hash(text: str) -> str:
    """The SHA-256 of the grammar's text, from CPython's built-in implementation when there is
    one: hashlib loads OpenSSL, a few milliseconds of every start-up."""
    try:
        from _sha2 import sha256  # CPython 3.12+
    except ImportError:
        try:
            from _sha256 import sha256  # CPython 3.11
        except ImportError:
            from hashlib import sha256
    return sha256(text.encode("utf-8")).hexdigest()


def tables_module():
    """The shipped tables module (imported, so from its .pyc)."""
    from ..grammar import glsl_tables

    return glsl_tables


def read_tables(module, grammar: str) -> dict[str, Any]:
    """The tables `module` holds; StaleTablesError unless they were built from `grammar` in this
    format."""
    if getattr(module, "FORMAT", None) != FORMAT:
        raise StaleTablesError(f"{module.__file__} has an old format")
    if module.GRAMMAR_SHA256 != grammar_hash(grammar):
        raise StaleTablesError(
            f"{module.__file__} was built from another version of {GRAMMAR_FILE}"
        )
    parser = {
        "start": module.START,
        "end": module.END,
        "rules": module.RULES,
        "actions": _unpack_actions(module.KEYS, module.ACTIONS),
    }
    return {
        "format": FORMAT,
        "grammar_sha256": module.GRAMMAR_SHA256,
        "built_by": module.BUILT_BY,
        "lexer": module.LEXER,
        "words": module.WORDS,
        "parser": parser,
    }


# How the module stores the LALR actions (`actions[state]`: terminal or rule name -> action, see
# frontend/lalr.py): the 404 states' 15 459 entries have only 113 distinct tuples of names, and more
# than half of the states do one thing whatever comes next (reduce by one rule). So the module lists
# the distinct name tuples once (`KEYS`, each as one string of space-separated names) and each
# state as `(index into KEYS, its actions)`, the actions one number when they are all the same,
# else the bytes of 16-bit little-endian numbers; `dict.fromkeys` / `dict(zip(...))` rebuild
# each state's dict. Strings and bytes, not tuples of thousands of numbers and names: where no
# .pyc can be written (PYTHONDONTWRITEBYTECODE, a read-only install), compiling a tuple per
# state cost more than twice the rest of the module (the same choice as base/_regex_code.py).
_ACTION = "<{}h"  # struct format of a state's actions


def _pack_actions(actions: list[dict[str, int]]) -> tuple[list[str], list[tuple]]:
    from struct import pack

    keys: list[str] = []
    index: dict[tuple[str, ...], int] = {}
    rows: list[tuple] = []
    for row in actions:
        names = tuple(row)
        if any(" " in name for name in names):
            raise ValueError(f"a name with a space in the LALR table: {names}")
        k = index.get(names)
        if k is None:
            k = index[names] = len(keys)
            keys.append(" ".join(names))
        values = tuple(row.values())
        rows.append(
            (k, values[0] if len(set(values)) == 1 else pack(_ACTION.format(len(values)), *values))
        )
    return keys, rows


def _unpack_actions(keys: tuple[str, ...], rows: tuple[tuple, ...]) -> list[dict[str, int]]:
    from struct import unpack

    names = [tuple(map(sys.intern, k.split(" "))) for k in keys]
    return [
        dict.fromkeys(names[k], v)
        if type(v) is int
        else dict(zip(names[k], unpack(_ACTION.format(len(v) >> 1), v)))
        for k, v in rows
    ]


def load() -> dict[str, Any]:
    """The tables for the installed grammar: the shipped module, or built in memory when it is
    stale."""
    grammar = grammar_text()
    try:
        return read_tables(tables_module(), grammar)
    except Exception as e:  # stale, or a damaged module (any error importing it): never fatal
        print(
            f"glslcheck: warning: {_why(e)}; building the parser tables in memory "
            f"(run `python -m glslcheck.frontend.parse_tables` to update the module)",
            file=sys.stderr,
        )
        return build(grammar)


def _why(error: Exception) -> str:
    if isinstance(error, StaleTablesError):
        return str(error)
    return f"the parser tables module does not load ({type(error).__name__}: {error})"


# ---------------------------------------------------------------------------------------------
# Building (needs Lark; run ahead of time, by tests and when the file is stale)
# ---------------------------------------------------------------------------------------------


def build_lark(grammar: str | None = None):
    """Lark's parser for the grammar, built in memory (no cache file)."""
    from lark import Lark

    return Lark(grammar if grammar is not None else grammar_text(), **LARK_OPTIONS)


def build(grammar: str) -> dict[str, Any]:
    """The tables of `grammar`, as the JSON-ready dict `load` returns."""
    from .lalr import tables_from_lark
    from .lexer import lexer_tables

    lark = build_lark(grammar)
    words = dict(_TOKEN_WORDS)
    for t in lark.terminals:
        if t.name not in words and t.pattern.type == "str":
            words[t.name] = f"'{t.pattern.value}'"
    import lark as lark_module

    return {
        "format": FORMAT,
        "grammar_sha256": grammar_hash(grammar),
        "built_by": f"lark {lark_module.__version__}",
        "lexer": lexer_tables(lark.lexer_conf),
        "parser": tables_from_lark(lark.parser.parser.parser),
        "words": words,
    }


def dumps(tables: dict[str, Any]) -> str:
    """The module's text: one line per rule, name tuple and LALR state, so a grammar change
    gives a readable diff. Dictionaries are written with their keys sorted."""
    keys, rows = _pack_actions(tables["parser"]["actions"])
    lines = [
        f'"""The parser\'s tables for {GRAMMAR_FILE} (see glslcheck/frontend/parse_tables.py).',
        "",
        'Written by `python -m glslcheck.frontend.parse_tables`; do not edit."""',
        "",
        f"FORMAT = {tables['format']!r}",
        f"GRAMMAR_SHA256 = {tables['grammar_sha256']!r}",
        f"BUILT_BY = {tables['built_by']!r}",
        f"LEXER = {_literal(tables['lexer'])}",
        f"WORDS = {_literal(tables['words'])}",
        f"START = {tables['parser']['start']!r}",
        f"END = {tables['parser']['end']!r}",
    ]
    for name, items in (("RULES", tables["parser"]["rules"]), ("KEYS", keys), ("ACTIONS", rows)):
        lines.append(f"{name} = (")
        lines.extend(f"    {_literal(item)}," for item in items)
        lines.append(")")
    return "\n".join(lines) + "\n"


def _literal(value) -> str:
    """`value` (JSON-like data) as a Python literal: lists as tuples, dictionaries sorted."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k!r}: {_literal(value[k])}" for k in sorted(value)) + "}"
    if isinstance(value, (list, tuple)):
        items = [_literal(v) for v in value]
        return f"({items[0]},)" if len(items) == 1 else "(" + ", ".join(items) + ")"
    if isinstance(value, str):
        return repr(str(value))  # a rule's origin is a Lark Token (a str subclass)
    return repr(value)


def main(argv: list[str] | None = None) -> int:
    """Rebuild glslcheck/grammar/glsl_tables.py from glsl.lark (run after editing the grammar)."""
    write_generated(os.path.join(grammar_folder(), TABLES_FILE), dumps(build(grammar_text())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
