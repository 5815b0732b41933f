"""The parser tables shipped beside the grammar (glslcheck/frontend/parse_tables.py).

The module (grammar/glsl_tables.py) must be what Lark builds from the shipped grammar today (a
grammar edit without `python -m glslcheck.frontend.parse_tables` fails here), and tables built from
another grammar, or a damaged module, must be detected at run time and not used.
"""

from __future__ import annotations

import shutil
import types

import pytest

from glslcheck.frontend import parse_tables
from glslcheck.frontend.lalr import Driver
from glslcheck.frontend.lexer import Lexer


def test_shipped_tables_are_built_from_the_shipped_grammar():
    import os

    path = os.path.join(parse_tables.grammar_folder(), parse_tables.TABLES_FILE)
    with open(path, encoding="utf-8") as f:
        shipped = f.read()
    fresh = parse_tables.dumps(parse_tables.build(parse_tables.grammar_text()))
    assert shipped == fresh, (
        "grammar/glsl_tables.py is stale: run `python -m glslcheck.frontend.parse_tables`"
    )


def test_loaded_tables_are_the_built_ones():
    """What `load` gives from the module (tuples, from the .pyc) equals what `build` gives
    (lists)."""

    def plain(value):
        if isinstance(value, dict):
            return {k: plain(v) for k, v in value.items()}
        if isinstance(value, (list, tuple)):
            return [plain(v) for v in value]
        return value

    loaded = parse_tables.load()
    built = parse_tables.build(parse_tables.grammar_text())
    assert plain(loaded) == plain(built)
    # each state's actions in the same order
    assert [list(row) for row in loaded["parser"]["actions"]] == [
        list(row) for row in built["parser"]["actions"]
    ]


def _module_from(path) -> types.ModuleType:
    """The tables module made from the text at `path` (as importing it would)."""
    module = types.ModuleType("glsl_tables_copy")
    module.__file__ = str(path)
    exec(compile(path.read_text(encoding="utf-8"), str(path), "exec"), module.__dict__)
    return module


@pytest.fixture
def grammar_copy(tmp_path, monkeypatch):
    """The grammar folder copied to tmp_path, and parse_tables reading from the copy."""
    folder = parse_tables.grammar_folder()
    for name in (parse_tables.GRAMMAR_FILE, parse_tables.TABLES_FILE):
        shutil.copy(f"{folder}/{name}", tmp_path / name)
    monkeypatch.setattr(parse_tables, "grammar_folder", lambda: str(tmp_path))
    monkeypatch.setattr(
        parse_tables, "tables_module", lambda: _module_from(tmp_path / parse_tables.TABLES_FILE)
    )
    return tmp_path


def test_unchanged_copy_loads_without_building(grammar_copy, monkeypatch, capsys):
    monkeypatch.setattr(
        parse_tables, "build", lambda grammar: pytest.fail("the tables were rebuilt")
    )
    tables = parse_tables.load()
    assert tables["grammar_sha256"] == parse_tables.grammar_hash(parse_tables.grammar_text())
    assert capsys.readouterr().err == ""


def test_stale_tables_are_detected_and_rebuilt_in_memory(grammar_copy, capsys):
    grammar = grammar_copy / parse_tables.GRAMMAR_FILE
    tables_file = grammar_copy / parse_tables.TABLES_FILE
    before = tables_file.read_bytes()
    # A grammar change the old tables do not know: `^^=` becomes an assignment operator.
    text = grammar.read_text(encoding="utf-8")
    assert '"^=" | "|="' in text
    grammar.write_text(text.replace('"^=" | "|="', '"^=" | "|=" | "^^="'), encoding="utf-8")
    with pytest.raises(parse_tables.StaleTablesError):
        parse_tables.read_tables(_module_from(tables_file), grammar.read_text(encoding="utf-8"))
    tables = parse_tables.load()
    assert "building the parser tables in memory" in capsys.readouterr().err
    assert tables["grammar_sha256"] == parse_tables.grammar_hash(
        grammar.read_text(encoding="utf-8")
    )
    # The rebuilt tables are the edited grammar's: the new operator lexes and parses.
    lexer, driver = Lexer(tables["lexer"]), Driver(tables["parser"])
    tree = driver.parse(lexer.tokenize("void f() { a ^^= b; }"))
    tokens = [
        child for sub in tree.iter_subtrees() for child in sub.children if isinstance(child, str)
    ]
    assert "^^=" in tokens
    assert tables_file.read_bytes() == before  # nothing written at run time


@pytest.mark.parametrize("damage", ["truncated", "old format"])
def test_damaged_tables_are_not_used(grammar_copy, capsys, damage):
    tables_file = grammar_copy / parse_tables.TABLES_FILE
    text = tables_file.read_text(encoding="utf-8")
    if damage == "truncated":
        tables_file.write_text(text[: len(text) // 2], encoding="utf-8")
    else:
        old = f"FORMAT = {parse_tables.FORMAT}\n"
        assert old in text
        tables_file.write_text(text.replace(old, "FORMAT = 2\n"), encoding="utf-8")
    tables = parse_tables.load()
    assert "building the parser tables in memory" in capsys.readouterr().err
    assert tables["format"] == parse_tables.FORMAT
