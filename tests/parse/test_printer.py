"""The printer's precedence table agrees with the grammar's ladder, and the printer keeps
meaning: printing then parsing gives the same tree for expressions needing parentheses."""

from __future__ import annotations

import itertools

import pytest

from glslcheck.frontend import syntax as A
from glslcheck.frontend.parser import parse_string
from glslcheck.frontend.printer import PRECEDENCE, to_glsl

BINARY = [
    "||",
    "^^",
    "&&",
    "|",
    "^",
    "&",
    "==",
    "!=",
    "<",
    ">",
    "<=",
    ">=",
    "<<",
    ">>",
    "+",
    "-",
    "*",
    "/",
    "%",
]


def _expr(text: str) -> A.Expr:
    tree = parse_string(f"void mainImage(out vec4 c, in vec2 f) {{ x = {text}; }}")
    (stmt,) = tree.decls[0].body.stmts
    return stmt.expr.value


@pytest.mark.parametrize("op1,op2", list(itertools.product(BINARY, BINARY)))
def test_grammar_and_table_agree(op1, op2):
    tree = _expr(f"a {op1} b {op2} c")
    # Left-associative at equal precedence; otherwise the tighter operator is the inner one.
    if PRECEDENCE[op1] >= PRECEDENCE[op2]:
        assert tree.op == op2 and isinstance(tree.left, A.Binary) and tree.left.op == op1
    else:
        assert tree.op == op1 and isinstance(tree.right, A.Binary) and tree.right.op == op2


@pytest.mark.parametrize(
    "text",
    [
        "(a + b) * c",
        "a - (b - c)",
        "a / (b * c)",
        "-(-a)",
        "- -a",
        "+(+a)",
        "!(a && b)",
        "(a, b)",
        "a ? b : c ? d : e",
        "(a ? b : c) ? d : e",
        "a = b = c",
        "(a = b) + c",
        "(a + b).x",
        "(1.0).x",
        "a[i + 1].yz",
        "vec3(a, b)[2]",
        "float[3](a, b, c)[1]",
        "a++ + ++b",
        "-a++",
        "(-a)++",
        "~(a | b) & c",
        "a << (b >> c)",
        "a < b == c > d",
    ],
)
def test_round_trip_keeps_meaning(text):
    program = f"void mainImage(out vec4 c, in vec2 f) {{ x = {text}; }}"
    tree = parse_string(program)
    again = parse_string(to_glsl(tree))
    assert A.dump(again) == A.dump(tree)
