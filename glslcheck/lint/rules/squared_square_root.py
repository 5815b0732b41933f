"""A square root is computed only to be squared.

## What it does
Reports the square of a square root: `x * x`, `pow(x, 2.0)` (the 2 may reach it through a
local) or a call of a user function that returns its one argument squared (`sq(x)`,
`square(x)`: a single `return p * p;`, `dot(p, p)` or `pow(p, 2.0)`), where `x` is `sqrt(e)`,
`length(v)` or `distance(a, b)`, written there or held in a local variable whose value from that
square root is read nowhere but in such squares (`float r = length(uv); r = pow(r, 2.0);`).
The square root's value squared is what it took the root of: `e`, `dot(v, v)`,
`dot(a - b, a - b)`. A square root that is also used as it is (`d / I + d * d / (I * I)`) is
not reported: there the root is needed and `d * d` is the cheap way to its square.

## Why is this bad?
The course's coding standards: "Use the most efficient methods (-1 per inefficient/unnecessary
practices) ... Use inefficient functions and methods sparingly and out of necessity (including
but not limited to conditionals, square roots, etc.)". Squaring a square root undoes it: the
square root was computed for nothing.

## Example
```glsl
float r = length(uv);
r = pow(r, 2.0);
float fall = 1.0 / square(length(toLight));
```

## Use instead
```glsl
float r = dot(uv, uv); // the squared length: no square root
float fall = 1.0 / dot(toLight, toLight);
```
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic
from ...frontend import syntax as A
from ...semantics.analysis import builtin_call, numbers, program_facts, pure_function
from ...semantics.model import Symbol
from ._text import text, wrap

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from ..engine import LintContext

NAME = "squared-square-root"
PENALTY = 1
STANDARD = "efficiency"
SEVERITY = "warning"
NEEDS = "ast"

_ROOTS = ("sqrt", "length", "distance")


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    for fn in program_facts(ctx.model).in_file(ctx.path):
        squares = [(n, x) for n in fn.nodes if (x := _squared(fn, n)) is not None]
        if not squares:
            continue
        # the identifiers squaring reads: a local's root read only there is wasted
        in_square = {id(x) for _, x in squares} | {
            id(n.right) for n, _ in squares if type(n) is A.Binary
        }
        for node, x in squares:
            root = _root(fn, x, in_square)
            if root is None:
                continue
            held = f" (held in '{x.name}', line {root.loc.line})" if x is not root else ""
            yield Diagnostic(
                f"'{text(node)}' squares {text(root)}{held}: the square root is computed only "
                "to be undone",
                node.loc,
                help=f"write {_square_of(root)}, which is that square without the square root",
            )


def _squared(fn, n) -> Any:
    """The operand `n` squares (`x * x`, `pow(x, 2.0)`, `sq(x)`), else None."""
    model = fn.model
    if type(n) is A.Binary and n.op == "*":
        if fn.key(n.left) == fn.key(n.right) and fn.is_pure(n.left):
            return n.left
        return None
    if type(n) is not A.Call or len(n.args) not in (1, 2):
        return None
    if builtin_call(model, n, "pow") and len(n.args) == 2:
        value, _ = fn.constant_through_locals(n.args[1])
        return n.args[0] if numbers(value) == [2.0] else None
    target = model.call_target(n)
    d = getattr(target, "node", None)
    if (
        len(n.args) != 1
        or not isinstance(target, Symbol)
        or not isinstance(d, A.FunctionDefinition)
        or d.body is None
        or len(d.body.stmts) != 1
        or len(d.proto.params) != 1
        or not pure_function(model, target)
    ):
        return None
    ret, param = d.body.stmts[0], d.proto.params[0].name
    if type(ret) is not A.Return or ret.value is None:
        return None
    v = ret.value

    def is_param(e) -> bool:
        return type(e) is A.Identifier and e.name == param

    if type(v) is A.Binary and v.op == "*" and is_param(v.left) and is_param(v.right):
        return n.args[0]
    if type(v) is A.Call and v.callee in ("dot", "pow") and len(v.args) == 2:
        if v.callee == "dot" and is_param(v.args[0]) and is_param(v.args[1]):
            return n.args[0]
        if (
            v.callee == "pow"
            and is_param(v.args[0])
            and numbers(model.const_value(v.args[1])) == [2.0]
        ):
            return n.args[0]
    return None


def _root(fn, x, in_square: set[int]) -> A.Call | None:
    """The square root `x` is (a call of sqrt, length or distance) or holds (a local assigned
    one, read nowhere but in squares while it holds it), else None."""
    model = fn.model
    if type(x) is A.Call:
        return x if builtin_call(model, x, *_ROOTS) else None
    if type(x) is not A.Identifier:
        return None
    sym = model.symbol_of(x)
    if sym is None or sym.kind != "local":
        return None
    value = fn.reaching_value(x, sym)
    if not builtin_call(model, value, *_ROOTS):
        return None
    # every read of the local that may see this value is a squaring's operand
    for n in fn.nodes:
        if type(n) is not A.Identifier or n is x or model.symbol_of(n) is not sym:
            continue
        if _written_whole(fn, n):
            continue
        seen = fn.reaching_value(n, sym)
        if (seen is None or seen is value) and id(n) not in in_square:
            return None
    return value


def _written_whole(fn, ident: A.Identifier) -> bool:
    """Whether `ident` is the target an `=` writes (not a read)."""
    parent = fn.parent.get(id(ident))
    return type(parent) is A.Assignment and parent.op == "=" and parent.target is ident


def _square_of(root: A.Call) -> str:
    if root.callee == "sqrt":
        return text(root.args[0])
    if root.callee == "length":
        v = text(root.args[0])
        return f"dot({v}, {v})"
    d = f"{wrap(root.args[0])} - {wrap(root.args[1])}"
    return f"dot({d}, {d})"
