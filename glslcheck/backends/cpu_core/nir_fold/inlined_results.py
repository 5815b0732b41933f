"""A user function's result as NIR sees it after inlining: ``hash(i+c)*hash(i+c)*0.7``.

Mesa inlines every function before nir_opt_algebraic runs, so the product sink
(sink.py, ``(a * b) * #c -> (a * #c) * b``) sees ``hash(x) * hash(x)`` as ``h * h`` with h
the ``fract`` the callee returns, and rewrites ``(h * h) * 0.7`` as ``(h * 0.7) * h``
(measured: iq's sdBase, ``length(f-c) - hash(i+c)*hash(i+c)*0.7``). The transpiler emits a
call of a user function as a call, which the rules treat as a side effect and leave as written.

Here a call counts as the value it returns where inlining adds nothing else: its function
qualifies (:func:`pure_function`) when, inlined, it is a value of its arguments only, so two
calls with the same arguments are one value after CSE and evaluating it again or in another
order changes nothing: every parameter ``in`` (an ``out`` writes the caller), no global
written (by it or a function it calls), no written global read (a value that may change
between two calls; the test, facts.reads_lane_state, also counts gl_FragCoord), no
``discard``, a straight-line body (declarations and expression statements, then its
:func:`final_return`: no branch, so one value on every path), and only qualifying user
functions called. Its result is what the final ``return`` gives, or the initializer of the
returned local when nothing else writes it (:func:`returned_value`); queries.opaque_call
counts the call as opaque where that result is (``fract(...)``, ``sin``: no rule looks into
it), and queries.stable_init sees a never-written local initialised by such a call (``float
r0 = hash(i); ... r0 * r0 * 0.55``). Other results (a product, a sum, a vector built in
components) are not copied: the rules would have to look into the callee's arithmetic."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....semantics.analysis import param_directions
from ....semantics.model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine


def called_function(tr: FoldEngine, call: Any) -> Symbol | None:
    """The user function a call names (not a built-in, not a constructor), else None."""
    if not isinstance(call, A.Call) or call.constructor:
        return None
    target = tr.model.call_target(call)
    return target if isinstance(target, Symbol) else None


def pure_function(tr: FoldEngine, fn: Symbol) -> bool:
    """Inlined, `fn` is a value of its arguments only (see the module doc)."""
    memo = tr.fold_state.pure_functions
    if id(fn) not in memo:
        memo[id(fn)] = False  # (GLSL forbids recursion; a cycle is no pure function either)
        memo[id(fn)] = _qualifies(tr, fn)
    return memo[id(fn)]


def _qualifies(tr: FoldEngine, fn: Symbol) -> bool:
    node = getattr(fn, "node", None)
    body = getattr(node, "body", None)
    if not isinstance(node, A.FunctionDefinition) or not isinstance(body, A.Compound):
        return False
    if any(d != "in" for d in param_directions(fn)) or not body.stmts:
        return False
    facts = tr.facts
    if id(fn) in facts.may_discard or id(fn) in facts.reads_lane_state or facts.writes_globals(fn):
        return False
    if final_return(fn) is None:
        return False
    steps = body.stmts[:-1]
    if not all(isinstance(s, (A.DeclarationStatement, A.ExpressionStatement)) for s in steps):
        return False
    for n in body.walk():
        if isinstance(n, A.Call) and not n.constructor:
            target = tr.model.call_target(n)
            if isinstance(target, Symbol):
                if not pure_function(tr, target):
                    return False
            elif any(d != "in" for d in param_directions(target)):
                return False  # (modf's out argument: a write the body order matters to)
    return True


def returned_value(tr: FoldEngine, call: Any) -> Any:
    """The expression a call of a qualifying user function returns: its final ``return``'s, or
    the initializer of the local it returns when only the declaration writes that local; None
    for any other call."""
    fn = called_function(tr, call)
    if fn is None or not pure_function(tr, fn):
        return None
    memo = tr.fold_state.returned_values
    if id(fn) not in memo:
        memo[id(fn)] = _returned(tr, fn)
    return memo[id(fn)]


def final_return(fn: Symbol) -> A.Return | None:
    """A user function's last statement when it is its one ``return`` and gives a value (one
    value on every path that returns), else None."""
    body = getattr(getattr(fn, "node", None), "body", None)
    if not isinstance(body, A.Compound) or not body.stmts:
        return None
    last = body.stmts[-1]
    if not (isinstance(last, A.Return) and last.value is not None):
        return None
    if sum(isinstance(n, A.Return) for n in body.walk()) != 1:
        return None
    return last


def only_return(tr: FoldEngine, fn: Symbol) -> Any:
    """The expression a user function's :func:`final_return` gives (or the initializer of the
    local it returns when only the declaration writes that local), for questions of the value's
    form alone (is it a b2f): unlike :func:`returned_value` the function may write out
    parameters and globals. None when it returns anywhere else."""
    return None if final_return(fn) is None else _returned(tr, fn)


def _returned(tr: FoldEngine, fn: Symbol) -> Any:
    value = fn.node.body.stmts[-1].value
    sym = tr.model.symbol_of(value) if isinstance(value, A.Identifier) else None
    if sym is None or sym.kind != "local" or not isinstance(sym.node, A.Declarator):
        return value
    if sym.node.init is None or any(
        sym in tr.facts.written_variables(n) for n in fn.node.body.walk()
    ):
        return value
    return sym.node.init
