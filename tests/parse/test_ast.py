"""The AST's declarations (glslcheck/frontend/syntax.py): children derived from the declared fields,
the generated constructors, and NodeVisitor's dispatch."""

from __future__ import annotations

import pickle
from pathlib import Path

import pytest

from glslcheck.frontend import syntax as A
from glslcheck.frontend.parser import parse_shader, parse_string
from glslcheck.shadertoy.sources import find_shaders

ROOT = Path(__file__).resolve().parents[2]
PROGRAMS = sorted(p for p in (ROOT / "tests" / "corpus").iterdir() if p.is_file()) + sorted(
    p for p in (ROOT / "lab_shaders").glob("*") if p.is_dir()
)


# What the corpus does not write (parsed, not checked): a struct defined in an array
# constructor, an array of interface blocks, a qualified condition declaration.
EXTRA = """float f() { return struct S { float a; }[2](S(1.0), S(2.0))[0].a; }
uniform Block { vec4 a; } blocks[2];
void g() { while (const bool b = true) { } }
"""


def _trees():
    for shader in find_shaders([str(p) for p in PROGRAMS]):
        for tab in [t for t in shader.tabs if t != "Common"] or ["Common"]:
            yield parse_shader(shader, tab).ast
    yield parse_string(EXTRA)


def test_children_are_exactly_the_fields_that_hold_nodes():
    """On every corpus and lab tree: a field is in `_children` if and only if it holds nodes."""
    holds_nodes: dict[type, set[str]] = {}
    seen: set[type] = set()
    for tree in _trees():
        for node in tree.walk():
            seen.add(type(node))
            for name in node._fields:
                value = getattr(node, name)
                items = value if isinstance(value, list) else [value]
                if any(isinstance(v, A.Node) for v in items):
                    holds_nodes.setdefault(type(node), set()).add(name)
                    assert name in node._children, f"{type(node).__name__}.{name} holds nodes"
                    assert all(v is None or isinstance(v, A.Node) for v in items)
                elif name in node._children:
                    assert all(v is None for v in items), (
                        f"{type(node).__name__}.{name} is a child field"
                    )
    # The corpus reaches every node class that has children, and each of its child fields.
    for cls in A._NODE_CLASSES.values():
        if cls._children and cls in seen:
            assert holds_nodes.get(cls, set()) == set(cls._children), cls.__name__


def test_children_follow_source_order():
    call = A.Call(
        callee="",
        struct_=A.StructSpec(name="S"),
        array=A.ArraySpec(),
        args=[A.Identifier(name="a")],
    )
    assert [type(c).__name__ for c in call.children()] == ["StructSpec", "ArraySpec", "Identifier"]


def test_constructors_repr_and_pickling():
    a, b = A.Compound(), A.Compound()
    assert a.stmts == [] and a.stmts is not b.stmts  # a fresh list per node
    ident = A.Identifier("x")  # positional, in field order
    assert ident.name == "x" and ident.loc.line == 0
    assert (
        repr(A.Binary(op="+", left=ident, right=None))
        == "Binary(op='+', left=Identifier(name='x'), right=None)"
    )
    with pytest.raises(TypeError):
        A.Identifier("x", loc=None, colour=1)
    with pytest.raises(AttributeError):
        ident.colour = 1  # slotted: no attribute outside the declaration
    again = pickle.loads(pickle.dumps(A.Return(value=ident)))
    assert A.dump(again) == A.dump(A.Return(value=ident))


class _Counter(A.NodeVisitor):
    def __init__(self) -> None:
        self.names: list[str] = []

    def visit_Identifier(self, node: A.Identifier) -> str:
        self.names.append(node.name)
        return node.name

    def visit_Expr(self, node: A.Expr) -> str:  # any other expression: its children, then a mark
        self.generic_visit(node)
        return "expr"

    def _depth_Node(self, node: A.Node, depth: int) -> int:
        return max([depth] + [self.dispatch("_depth_", c, depth + 1) for c in node.children()])


def test_node_visitor_dispatches_by_class_then_bases_and_returns():
    tree = A.Binary(
        op="+", left=A.Identifier(name="a"), right=A.Unary(op="-", operand=A.Identifier(name="b"))
    )
    v = _Counter()
    assert v.visit(tree.left) == "a"
    assert v.visit(tree) == "expr"  # no visit_Binary: the base class's method
    assert v.names == ["a", "a", "b"]
    assert v.visit(A.Return(value=A.Identifier(name="c"))) is None  # generic_visit for statements
    assert v.names[-1] == "c"
    assert v.dispatch("_depth_", tree, 0) == 2  # another method family, with an argument
    with pytest.raises(TypeError, match="has no _size_Binary"):
        v.dispatch("_size_", tree)
