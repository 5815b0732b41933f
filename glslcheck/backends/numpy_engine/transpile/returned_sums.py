"""A constant added to a call's result, sunk into the ``+=`` chain the function returns
(cpu_core/nir_fold/returned_sums.py), written by the NumPy transpiler: the call passed the
constant, the callee's terms kept in temporaries and its return adding the constant where NIR
puts it."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....semantics.model import Symbol
from ...cpu_core.common import sum_in_order
from ...cpu_core.nir_fold.queries import FunctionStandin, current_function
from ...cpu_core.nir_fold.returned_sums import sunk_call, sunk_order, sunk_return

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .state import TranspilerState


def sink_into_call(tr: TranspilerState, e: A.Binary, mask: str | None) -> str | None:
    """``f(...) +- #c`` of a :func:`sunk_call`: the call, passed the constant in llvmpipe mode
    (the callee adds it where NIR sinks it), else None."""
    sunk = sunk_call(tr, e)
    if sunk is None:
        return None
    call, k, negative = sunk
    tk = tr.expr(k, mask)
    signed = f"(-{tk})" if negative else tk
    tr.fold_state.call_k[id(call)] = f"({signed} if rt.lp else None)"
    result = tr.tmp(tr.expr(call, mask))
    return f"({result} if rt.lp else ({result} {e.op} {tk}))"


def return_constant_args(tr: TranspilerState, call: A.Call, fn: Symbol) -> list[str]:
    """The extra argument of a call of a function with a :func:`sunk_return`: the constant the
    caller adds (:func:`sink._sink_sum`, llvmpipe mode) or None; [] for other functions."""
    if sunk_return(tr, fn) is None:
        return []
    return [tr.fold_state.call_k.get(id(call), "None")]


def keep_term(tr: TranspilerState, node: Any, code: str) -> str:
    """The code of a term of a :func:`sunk_return` sum, kept in a temporary; other values as
    they are. ``node``: the assignment or declarator that writes it."""
    if tr.fn is None or isinstance(tr.fn, FunctionStandin):
        return code
    chain = sunk_return(tr, current_function(tr).sym)
    if chain is None or not any(w is node for w, _, _ in chain):
        return code
    t = tr.tmp(code)
    tr.fold_state.terms[id(node)] = t
    return t


def sunk_return_value(tr: TranspilerState, ret: A.Return, code: str | None) -> str | None:
    """The returned value of a function with a :func:`sunk_return`: ``code`` when the caller
    adds nothing (``_k`` None), else the sum with the constant sunk as NIR sinks it."""
    chain = sunk_return(tr, current_function(tr).sym) if tr.fn is not None else None
    terms = tr.fold_state.terms
    if chain is None or ret.value is None or not all(id(w) in terms for w, _, _ in chain):
        return code
    sunk = sum_in_order(sunk_order(tr, chain), [terms[id(w)] for w, _, _ in chain], "_k")
    return f"({code} if _k is None else {sunk})"
