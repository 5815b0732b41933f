"""Whether NIR unrolls a loop: a ``for`` of a constant count, and a body small enough.

Mesa 22.3's nir_opt_loop_unroll unrolls a loop whose trip count its analysis finds when that
count is at most the driver's max_unroll_iterations (32 for llvmpipe) and the body's cost
times the count is at most 32 * 26 = 832 (check_unrolling_restrictions, LOOP_UNROLL_LIMIT).
The cost counts the body's ALU instructions after NIR splits vectors into components; the
induction variable's increment and the loop's own test are free. Measured on llvmpipe (a
chain of ``+= 0.1`` in the body, whose constants merge across passes only when the loop is
unrolled): 16 passes of ``a = sin(a * 1.01 + k)`` lines (3 instructions each) and two
additions are unrolled with 16 lines and not with 17; 8 passes with 34 and not 35; the same
lines on a vec3, 9 instructions each, with 5 and not 6: cost 3n + 2 (9n + 2) times the count
against 832. The same way, lines of ``a = atan(a * 1.01 + k)`` and of ``a = atan(a * 1.01 + k,
a + 0.5)`` among sin lines: 13 unrolled and 14 kept in 2 passes, 8 and 9 in 3, 6 and 7 in 4,
one atan line with 57 sin lines and 3 of ``a = sin(a)`` unrolled in 4 passes, with 4 kept, one
atan(y, x) line with 49 and 5 unrolled, with 6 kept: atan costs 29 a component and atan(y, x)
50, where the two additions and the loop cost 3 (the sin lines leave 2 to 4; only 3 agrees with
every atan count). Four such additions in the body of 16 sin lines still unroll 16 passes: the
additions of constants are one once merged, the loop's own instructions 2, where the count here
takes every addition for one and the loop for none (2 for the two additions: one short).

The cost here is counted on the syntax tree (:func:`body_cost`): an operator or a built-in is
its result's components (a ``dot`` of N components 2N - 1 instructions, a ``normalize`` 3N, a
few built-ins more, a table), a user function what its body costs (NIR inlines it), a
constructor or a swizzle nothing, a constant expression nothing; a loop inside (here or in a
callee) is taken as keeping the outer loop. It does not see what NIR's other passes remove or
add before the loop is unrolled (common subexpressions, dead code), so a body close to the
limit may be judged otherwise than Mesa does (the inout-seed path tracer of
tests/gl/test_llvmpipe_path_tracers.py counts 156 of the 166 its 5 passes may cost)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....semantics.model import Symbol
from ..facts import induction_variable

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine

MAX_ITERATIONS = 32  # llvmpipe's max_unroll_iterations
UNROLL_LIMIT = 26  # nir_opt_loop_unroll.c LOOP_UNROLL_LIMIT

# instructions a component of some built-ins costs once NIR has lowered them (one for the rest)
_PER_COMPONENT = {
    "clamp": 2,
    "mix": 3,
    "smoothstep": 6,
    "mod": 4,
    "tan": 3,
    "atan": 29,  # (one argument; two: ATAN2)
    "asin": 10,
    "acos": 10,
    "sinh": 6,
    "cosh": 6,
    "tanh": 8,
    "step": 2,
    "fract": 2,
    "radians": 1,
    "degrees": 1,
}
ATAN2 = 50  # atan(y, x), a component


def trip_count(tr: FoldEngine, loop: Any) -> int | None:
    """The passes of a ``for`` whose induction variable runs from a constant to a constant by a
    constant step (``i < n`` or ``i <= n``), else None."""
    if not isinstance(loop, A.For) or induction_variable(loop, tr.model) is None:
        return None
    init = loop.init  # an induction variable's declaration (induction_variable)
    assert isinstance(init, A.DeclarationStatement) and isinstance(init.decl, A.VariableDeclaration)
    decl = init.decl.declarators[0]
    start, cond, step = tr.model.const_value(decl.init), loop.cond, loop.step
    if not (
        isinstance(start, int)
        and isinstance(cond, A.Binary)
        and cond.op in ("<", "<=")
        and isinstance(cond.left, A.Identifier)
        and tr.model.symbol_of(cond.left) is tr.model.symbol_of(decl)
    ):
        return None
    end = tr.model.const_value(cond.right)
    inc = (
        1
        if isinstance(step, (A.Unary, A.Postfix)) and step.op == "++"
        else (
            tr.model.const_value(step.value)
            if isinstance(step, A.Assignment) and step.op == "+="
            else None
        )
    )
    if not isinstance(end, int) or not isinstance(inc, int) or inc <= 0:
        return None
    return max(0, (end - start + (cond.op == "<=") + inc - 1) // inc)


def nir_unrolls(tr: FoldEngine, loop: Any) -> bool:
    """NIR unrolls `loop`: a constant count of at most 32 passes, and a body whose cost times
    the count is within the limit."""
    count = trip_count(tr, loop)
    if count is None or count > MAX_ITERATIONS:
        return False
    cache = tr.fold_state.loop_costs
    if id(loop) not in cache:
        var = tr.model.symbol_of(loop.init.decl.declarators[0])
        cache[id(loop)] = body_cost(tr, loop.body, var, 0)
    return cache[id(loop)] * count <= MAX_ITERATIONS * UNROLL_LIMIT


def body_cost(tr: FoldEngine, node: Any, induction: Any, depth: int) -> int:
    """NIR's instructions for `node`, roughly (see the module docstring); the operations on
    the induction variable `induction` are free."""
    too_much = MAX_ITERATIONS * UNROLL_LIMIT + 1
    if depth > 8:
        return too_much  # (calls nested deeper: too much to unroll anyway)
    cost = 0
    for n in node.walk():
        if isinstance(n, (A.For, A.While, A.DoWhile)):
            return too_much  # (a loop inside, here or in a callee: NIR unrolls only innermost)
        cost += _own_cost(tr, n, induction, depth)
    return cost


def _components(tr: FoldEngine, e: Any) -> int:
    t = tr.type_of(e)
    if t is None:
        return 1
    if t.is_matrix:
        return t.cols * t.rows
    return t.size if t.is_vector else 1


def _on_induction(tr: FoldEngine, n: Any, induction: Any) -> bool:
    operand = getattr(n, "operand", None) if isinstance(n, (A.Unary, A.Postfix)) else None
    target = n.target if isinstance(n, A.Assignment) else operand
    return isinstance(target, A.Identifier) and tr.model.symbol_of(target) is induction


def _own_cost(tr: FoldEngine, n: Any, induction: Any, depth: int) -> int:
    if (
        isinstance(n, (A.Binary, A.Unary, A.Call, A.Ternary))
        and tr.model.const_value(n) is not None
    ):
        return 0  # (folded before the loop is unrolled)
    if isinstance(n, A.Binary):
        if n.op in ("&&", "||"):
            return 1
        lt, rt = tr.type_of(n.left), tr.type_of(n.right)
        if n.op == "*" and lt is not None and rt is not None and (lt.is_matrix or rt.is_matrix):
            m = lt if lt.is_matrix else rt
            return 2 * m.cols * m.rows
        return max(_components(tr, n.left), _components(tr, n.right))
    if isinstance(n, (A.Unary, A.Postfix)):
        if n.op == "+" or _on_induction(tr, n, induction):
            return 0
        return 1 if n.op == "!" else _components(tr, n)
    if isinstance(n, A.Assignment):
        return 0 if n.op == "=" or _on_induction(tr, n, induction) else _components(tr, n)
    if isinstance(n, A.Ternary):
        return _components(tr, n)
    if isinstance(n, A.Call):
        target = tr.model.call_target(n)
        if isinstance(target, Symbol):
            return body_cost(tr, target.node.body, None, depth + 1)
        if not hasattr(target, "qualifiers"):  # (a constructor: a conversion costs its components)
            args = [tr.type_of(a) for a in n.args]
            t = tr.type_of(n)
            differs = t is not None and any(a is not None and a.base != t.base for a in args)
            return _components(tr, n) if differs else 0
        size = max([_components(tr, a) for a in n.args] or [1])
        if n.callee == "dot":
            return 2 * size - 1
        if n.callee == "length":
            return 2 * size
        if n.callee == "distance":
            return 3 * size
        if n.callee == "normalize":
            return 3 * size + 1
        if n.callee == "cross":
            return 9
        if n.callee == "reflect":
            return 4 * size
        if n.callee == "atan" and len(n.args) == 2:
            return ATAN2 * _components(tr, n)
        return _PER_COMPONENT.get(n.callee, 1) * _components(tr, n)
    return 0
