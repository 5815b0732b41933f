"""A squared length is its dot product: ``pow(length(x), 2.0) + #c`` is ``dot(x, x) + #c``.

To NIR ``pow(L, 2.0)`` is ``L * L`` (``fpow(a, 2.0) -> a * a``) and ``fsqrt(a) * fsqrt(a)`` is
a, so a squared ``length(x)`` or ``distance(x, #0)`` is ``dot(x, x)``, and a constant added to
it sinks into the dot product's innermost addition (sink.py) unless another length, normalize
or dot of x shares that dot product after CSE (:func:`shared_dot`), and then only where the
argument is a phi at every call (:func:`merged_argument`). Gargantua's ``1.0 /
(pow(distance(raypos, origin), 2.0) + 0.000001)`` differs in 6,014 of 14,400 pixels
otherwise."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from .queries import (
    asked_in,
    constant_value,
    current_function,
    function_facts,
    is_builtin,
    stable_init,
    written_symbols,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine


def squared_length(tr: FoldEngine, node: Any) -> Any:
    """x when ``node`` is ``pow(L, 2.0)`` and L is ``length(x)`` or ``distance(x, #0)`` (or a
    never-written local initialised so), x a parameter the function never writes: to NIR
    ``fsqrt(dot(x, x))`` squared is the dot product itself (fpow(a, 2.0) -> a*a, then
    sqrt(a)*sqrt(a) -> a), so ``pow(L, 2.0) + #c`` is ``dot(x, x) + #c`` with the constant in
    its innermost addition (measured: gargantua's ``1.0 / (pow(distance(raypos, origin),
    2.0) + 0.000001)``, 14,400 of 14,400 pixels; the written ``sqrt(d)*sqrt(d) + c`` differs
    in 6,014); else None."""
    if not (
        isinstance(node, A.Call)
        and node.callee == "pow"
        and is_builtin(tr, node)
        and len(node.args) == 2
        and constant_value(tr, node.args[1]) == [2.0]
        and tr.type_of(node).is_scalar
    ):
        return None
    length = node.args[0]
    if isinstance(length, A.Identifier):
        length = stable_init(tr, length)
    if not (
        isinstance(length, A.Call)
        and is_builtin(tr, length)
        and length.callee in ("length", "distance")
    ):
        return None
    args = list(length.args)
    if length.callee == "distance":
        zero = [
            a
            for a in args
            if (constant_value(tr, a) or [1.0]) and not any(constant_value(tr, a) or [1.0])
        ]
        if len(zero) != 1:
            return None
        args.remove(zero[0])
    x = args[0]
    sym = tr.model.symbol_of(x) if isinstance(x, A.Identifier) else None
    if (
        sym is None
        or sym.kind != "param"
        or id(sym) in written_symbols(tr)
        or not tr.type_of(x).is_vector
    ):
        return None
    return x


def shared_dot(tr: FoldEngine, x: Any, pow_call: Any) -> bool:
    """Another ``length``, ``distance``, ``normalize`` or ``dot`` of the current function reads
    the parameter x (alone, negated or subtracted from a constant): after inlining and CSE its
    ``dot(x, x)`` is the squared length's too, used twice, and a constant added to one of them
    stays outside (measured: ``glow(r) = pow(length(r), 2.0) - 0.37`` beside ``warp(r)``)."""
    sym = tr.model.symbol_of(x)
    own = set()
    for n in pow_call.walk():
        own.add(id(n))
    init = stable_init(tr, pow_call.args[0]) if isinstance(pow_call.args[0], A.Identifier) else None
    for n in init.walk() if init is not None else ():
        own.add(id(n))
    for n in current_function(tr).sym.node.body.walk():
        if (
            id(n) in own
            or not isinstance(n, A.Call)
            or n.callee not in ("length", "distance", "normalize", "dot")
            or not is_builtin(tr, n)
        ):
            continue
        for a in n.args:
            while (
                isinstance(a, A.Unary)
                and a.op == "-"
                or isinstance(a, A.Binary)
                and a.op == "-"
                and (constant_value(tr, a.left) is not None)
            ):
                a = a.operand if isinstance(a, A.Unary) else a.right
            if isinstance(a, A.Identifier) and tr.model.symbol_of(a) is sym:
                return True
    return False


def merged_argument(tr: Any, x: Any) -> bool:  # (sets tr.fn for a while)
    """Every call of the current function passes for the parameter x a variable whose value
    there merges several writes (to NIR a phi: written in a loop around the call, or last
    written in a branch before it). Then the constant joins the shared dot product's innermost
    addition after all: nir_opt_algebraic's ``(a + b) + #c`` sink (``fadd(is_used_once)``)
    runs before CSE has merged the two dot products when x is a phi, after it when x is an
    ALU value (measured on a copy of gargantua's WarpSpace, 14,400 pixels each: called in a
    loop that writes x, 0 pixels off sunk and 1-3 outside; after an ``if`` that writes x, 0
    and 1; in a loop that does not write x, or after straight-line writes, 1 sunk and 0
    outside). Which pass ordering makes a phi differ was not traced in Mesa's source."""
    fn = current_function(tr).sym
    names = [name for name, _, _ in fn.params]
    if x.name not in names:
        return False
    index = names.index(x.name)
    found = False
    for caller in tr.model.reachable_functions():
        for call in caller.node.body.walk():
            if not (isinstance(call, A.Call) and tr.model.call_target(call) is fn):
                continue
            arg = call.args[index] if index < len(call.args) else None
            sym = tr.model.symbol_of(arg) if isinstance(arg, A.Identifier) else None
            if sym is None or sym.kind not in ("local", "param"):
                return False
            with asked_in(tr, caller):
                facts = function_facts(tr)
            if not facts.ok or id(arg) not in facts.enter:
                return False
            # (the out write of a call of this function, which never writes x, changes nothing)
            writes = [
                w
                for w in facts.writes_to(sym)
                if not (
                    w.kind == "out"
                    and isinstance(w.node, A.Call)
                    and tr.model.call_target(w.node) is fn
                )
            ]
            at = facts.enter[id(arg)]
            before = [w for w in writes if w.pos < at]
            if not before:
                return False
            last = before[-1]
            merged = not facts.dominates(last.node, arg)
            if not merged:
                outer = {id(loop) for loop in facts.enclosing_loops(last.node)}
                merged = any(
                    facts.enter[id(loop)] <= w.pos <= facts.exit[id(loop)]
                    for loop in facts.enclosing_loops(arg)
                    if id(loop) not in outer
                    for w in writes
                )
            if not merged:
                return False
            found = True
    return found
