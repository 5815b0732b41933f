"""The corpus in tests/corpus: every shader parses, prints back to the same tree, and together
the corpus hits every rule and every keyword/operator terminal of grammar/glsl.lark."""

from __future__ import annotations

from pathlib import Path

import pytest

from glslcheck.frontend import syntax as A
from glslcheck.frontend.lalr import Tree
from glslcheck.frontend.parse_tables import build_lark
from glslcheck.frontend.parser import parse_shader, parse_tree, parse_units
from glslcheck.frontend.printer import to_glsl
from glslcheck.shadertoy.sources import Source, find_shaders

ROOT = Path(__file__).resolve().parents[2]
CORPUS = sorted(p for p in (ROOT / "tests" / "corpus").iterdir() if p.is_file())
LAB = sorted(p for p in (ROOT / "lab_shaders").glob("*") if p.is_dir())


def _programs(paths):
    for shader in find_shaders([str(p) for p in paths]):
        for tab in [t for t in shader.tabs if t != "Common"] or ["Common"]:
            yield shader, tab


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: p.name)
def test_corpus_parses_and_round_trips(path):
    (shader,) = find_shaders([str(path)])
    result = parse_shader(shader, shader.image.tab)
    printed = to_glsl(result.ast)
    # Print -> parse again. The printed text has no macros left; parse it as a plain unit
    # (not as a Shadertoy tab) when the original was plain GLSL, since #version is gone.
    again = parse_units([Source(str(path) + ".printed", printed)], shadertoy=True).ast
    assert A.dump(again) == A.dump(result.ast)
    # Printing is a fixed point after one round.
    assert to_glsl(again) == printed


@pytest.mark.parametrize("folder", LAB, ids=lambda p: p.name)
def test_lab_shaders_parse_and_round_trip(folder):
    for shader, tab in _programs([folder]):
        result = parse_shader(shader, tab)
        again = parse_units([Source("printed", to_glsl(result.ast))]).ast
        assert A.dump(again) == A.dump(result.ast)


def _parse_tree(path: Path) -> Tree:
    """The raw parse tree of a corpus file (for grammar coverage)."""
    from glslcheck.frontend.preprocess import preprocess

    (shader,) = find_shaders([str(path)])
    units = shader.units_for(shader.image.tab)
    pp = preprocess(units, shadertoy=not units[-1].is_plain_glsl)
    return parse_tree(pp.text)


def test_corpus_hits_every_grammar_rule_and_terminal():
    lark = build_lark()
    expected_trees: set[str] = set()
    for rule in lark.rules:
        name = rule.alias or rule.origin.name
        name = str(getattr(name, "name", name))
        if name.startswith("__"):
            continue  # Lark's own helper rules for `*`, `+` and `[]`, inlined into their parent
        kept = [s for s in rule.expansion if not getattr(s, "filter_out", False)]
        if rule.alias or not rule.options.expand1 or len(kept) > 1:
            # An inlined (?rule) alternative keeps a tree of its own only when it has several
            # children; `"(" expression ")"` collapses to the expression.
            expected_trees.add(name)
    expected_trees.discard("start")
    seen_trees: set[str] = set()
    seen_terminals: set[str] = set()
    for path in CORPUS:
        tree = _parse_tree(path)
        for sub in tree.iter_subtrees():
            seen_trees.add(str(sub.data))
            for child in sub.children:
                if hasattr(child, "type"):
                    seen_terminals.add(child.type)
    # Punctuation is filtered from the tree; keywords and operators kept by `!` rules are not.
    kept_terminals = {t.name for t in lark.terminals if t.pattern.type == "str"}
    filtered = {
        "LPAR",
        "RPAR",
        "LBRACE",
        "RBRACE",
        "LSQB",
        "RSQB",
        "SEMICOLON",
        "COMMA",
        "COLON",
        "QMARK",
        "DOT",
    }
    keywords_in_rules = {t for t in kept_terminals if t not in filtered}
    # Keywords consumed without being kept (if, while, struct, ...) are checked via the rules
    # that contain them, which the tree check covers.
    consumed = {
        "IF",
        "ELSE",
        "WHILE",
        "DO",
        "FOR",
        "SWITCH",
        "CASE",
        "DEFAULT",
        "BREAK",
        "CONTINUE",
        "RETURN",
        "DISCARD",
        "STRUCT",
        "PRECISION",
        "LAYOUT",
        "SHARED",
    }
    missing_trees = expected_trees - seen_trees
    missing_terminals = {t for t in keywords_in_rules - consumed if t not in seen_terminals}
    assert not missing_trees, f"grammar rules no corpus shader uses: {sorted(missing_trees)}"
    assert not missing_terminals, f"terminals no corpus shader uses: {sorted(missing_terminals)}"
