"""A call's result in the lanes a mask leaves out: llvmpipe's register for merged returns.

After inlining, NIR merges returns from inside a branch into one value (a phi); a branch
computed by a built-in call is too costly to flatten into selects, so the phi becomes a
register, stored under the exec mask, and a neighbour's derivative reads in a lane that left
the value of the last time the call ran for it (gargantua's GasDisc, measured), in a loop NIR
does not unroll (:func:`register_call`; the runtime keeps the value: frame.Lanes.reg)."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from .loop_unroll import nir_unrolls
from .queries import current_function

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ....semantics.model import Symbol
    from ..fold_protocols import FoldEngine


def register_call(tr: FoldEngine, call: A.Call, fn: Symbol) -> bool:
    """The result of this call of ``fn``, made under a mask in a function that takes
    derivatives, is llvmpipe's register in the lanes the mask leaves out: they keep the value
    they had the last time this call ran for them (frame.Lanes.reg).

    After inlining, NIR merges returns from inside a branch into one value (a phi); a branch
    computed by a built-in call (atan, pow, ...) is too costly to flatten into selects, so the
    phi becomes a register, stored under the exec mask, and a neighbour's derivative reads the
    old value in a lane that left (gargantua's GasDisc: ``atan2`` called after
    ``if (coverage < 0.01) return;`` in its 200-step loop, measured: the lane's value of the
    iteration before). Only in a loop NIR keeps (loop_unroll.nir_unrolls: a constant count of
    at most 32 passes and a body cheap enough): a loop it unrolls has each copy its own
    register, zero in such a lane (measured on a 4-step loop: the register kept across
    iterations put 917 of 14,400 pixels off, zero none; 6 steps with 24 lines of sin more in
    the body are kept: zero there put 1,522 off, the register none)."""
    if (
        tr.fn is None
        or id(current_function(tr).sym) not in tr.facts.uses_derivs
        or not _returns_in_branch(tr, fn)
    ):
        return False
    return _in_kept_loop(tr, current_function(tr).sym, call, 0)


def _returns_in_branch(tr: FoldEngine, fn: Symbol) -> bool:
    """``fn`` returns a value from inside an ``if`` or a loop, computed there by a call."""
    if fn.type is None or str(fn.type) == "void":
        return False
    for n in fn.node.body.walk():
        if isinstance(n, (A.If, A.For, A.While, A.DoWhile)) and any(
            isinstance(r, A.Return)
            and r.value is not None
            and any(isinstance(c, A.Call) and not c.constructor for c in r.value.walk())
            for r in n.walk()
        ):
            return True
    return False


def _in_kept_loop(tr: FoldEngine, sym: Symbol, node: Any, depth: int) -> bool:
    """``node`` (in function ``sym``) runs again and again in one invocation: its innermost
    loop, here or around every call of the function, is one NIR does not unroll."""
    from ....semantics.analysis.dataflow import FunctionFacts

    if depth > 8:
        return False
    cache = tr.fold_state.fn_facts
    if id(sym) not in cache:
        cache[id(sym)] = FunctionFacts(sym.node, tr.model)
    facts = cache[id(sym)]
    if not facts.ok or id(node) not in facts.enter:
        return False
    loops = facts.enclosing_loops(node)
    if loops:
        return not nir_unrolls(tr, loops[-1])
    sites = [
        (f, n)
        for f in tr.facts.functions
        for n in f.node.body.walk()
        if isinstance(n, A.Call) and tr.model.call_target(n) is sym
    ]
    return bool(sites) and all(_in_kept_loop(tr, f, n, depth + 1) for f, n in sites)
