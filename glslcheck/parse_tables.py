"""The parser's tables: built from grammar/glsl.lark by Lark, shipped as data, loaded at start-up.

Owns the one step that needs Lark: turning the grammar into what lexer.py and lalr.py run on
(the lexer's master regular expression and keyword tables, the LALR action table, and for each
rule the shape of the tree it builds). Lark does that analysis in about a second, so it is done
ahead of time and the result ships in the package as `glslcheck/grammar/glsl_tables.json`:
plain JSON, never a pickle, and never written at run time, so no cache file exists that
another user could plant (issue 16) and a CLI call does not import Lark (issue 18).

The file records the SHA-256 of the grammar it was built from. `load()` compares it with the
grammar that ships beside it; a stale file (the grammar was edited and the tables were not
rebuilt) is not used: the tables are built in memory from the grammar, with a warning, and
nothing is written. Rebuild the file after editing the grammar with

    python -m glslcheck.parse_tables

tests/parse/test_parse_tables.py checks that the shipped file is the one this module builds
from the shipped grammar, and that a stale file is detected.
"""

from __future__ import annotations

import json
import os
import sys

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up (issue 18)
if TYPE_CHECKING:
    from typing import Any

TABLES_FILE = "glsl_tables.json"
GRAMMAR_FILE = "glsl.lark"
FORMAT = 2  # bump when the layout of the JSON changes

# The Lark options the tables are built with (Lark is only used here, ahead of time).
LARK_OPTIONS = dict(
    parser="lalr",
    # Lark's basic lexer, not the contextual one, is the lexer lexer.py reproduces: a
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
    from . import grammar

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


def read_tables(path: str, grammar: str) -> dict[str, Any]:
    """The tables in `path`; StaleTablesError unless they were built from `grammar` in this format."""
    with open(path, encoding="utf-8") as f:
        tables = json.load(f)
    if not isinstance(tables, dict) or tables.get("format") != FORMAT:
        raise StaleTablesError(f"{path} has an old format")
    if tables.get("grammar_sha256") != grammar_hash(grammar):
        raise StaleTablesError(f"{path} was built from another version of {GRAMMAR_FILE}")
    parser = tables["parser"]
    parser["actions"] = _unpack_actions(parser.pop("keys"), parser["actions"])
    return tables


# How the file stores the LALR actions (`actions[state]`: terminal or rule name -> action, see
# lalr.py): the 404 states' 15 459 entries have only 113 distinct lists of names, and more than
# half of the states do one thing whatever comes next (reduce by one rule). So the file lists
# the distinct name lists once (`keys`) and each state as `[index into keys, its actions]`, the
# actions one number when they are all the same: JSON then reads a fifth of the strings and
# half of the numbers, and `dict.fromkeys` / `dict(zip(...))` rebuild each state's dict.


def _pack_actions(actions: list[dict[str, int]]) -> tuple[list[list[str]], list[list]]:
    keys: list[list[str]] = []
    index: dict[tuple[str, ...], int] = {}
    rows: list[list] = []
    for row in actions:
        names = tuple(row)
        k = index.get(names)
        if k is None:
            k = index[names] = len(keys)
            keys.append(list(names))
        values = list(row.values())
        rows.append([k, values[0] if len(set(values)) == 1 else values])
    return keys, rows


def _unpack_actions(keys: list[list[str]], rows: list[list]) -> list[dict[str, int]]:
    return [dict.fromkeys(keys[k], v) if type(v) is int else dict(zip(keys[k], v)) for k, v in rows]


def load() -> dict[str, Any]:
    """The tables for the installed grammar: the shipped file, or built in memory when it is stale."""
    folder = grammar_folder()
    grammar = grammar_text()
    path = os.path.join(folder, TABLES_FILE)
    try:
        return read_tables(path, grammar)
    except (OSError, ValueError, StaleTablesError) as e:
        print(f"glslcheck: warning: {e}; building the parser tables in memory "
              f"(run `python -m glslcheck.parse_tables` to update the file)", file=sys.stderr)
        return build(grammar)


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
    """The file's text: one line per LALR state, so a grammar change gives a readable diff."""
    keys, rows = _pack_actions(tables["parser"]["actions"])
    parser = {**tables["parser"], "keys": keys, "actions": rows}
    head = {k: v for k, v in tables.items() if k != "parser"}
    lines = ["{"]
    for key, value in head.items():
        lines.append(f"  {json.dumps(key)}: {json.dumps(value, sort_keys=True)},")
    lines.append('  "parser": {')
    for key, value in parser.items():
        if key in ("actions", "rules", "keys"):
            rows = [f"    {json.dumps(row, sort_keys=True)}" for row in value]
            lines.append(f"   {json.dumps(key)}: [\n" + ",\n".join(rows) + "\n   ],")
        else:
            lines.append(f"   {json.dumps(key)}: {json.dumps(value)},")
    lines[-1] = lines[-1].rstrip(",")
    lines.append("  }")
    lines.append("}")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Rebuild glslcheck/grammar/glsl_tables.json from glsl.lark (run after editing the grammar)."""
    write_generated(os.path.join(grammar_folder(), TABLES_FILE), dumps(build(grammar_text())))
    return 0


def write_generated(path: str, text: str) -> None:
    """Replace a generated file in one step (a reader never sees half of it) and say so."""
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)
    print(f"wrote {path}")


def write_generated_module(name: str, text: str) -> None:
    """`write_generated` for a module of the glslcheck package (`_regex_code.py`, `_init_code.py`)."""
    write_generated(os.path.join(os.path.dirname(os.path.abspath(__file__)), name), text)


if __name__ == "__main__":
    sys.exit(main())
