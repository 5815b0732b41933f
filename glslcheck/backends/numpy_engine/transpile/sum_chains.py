"""A variable advanced by constants (cpu_core/nir_fold/repeated_sums.py), written by the NumPy
transpiler: a step of a chain as ``base + K`` in llvmpipe mode, the value before the chain kept
in a temporary, a chain parameter's base and constants passed to the callee as two more
arguments, and the pass count of an unrolled loop whose copies read different constants."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....semantics.model import Symbol
from ...cpu_core.nir_fold.loop_copies import later_values
from ...cpu_core.nir_fold.queries import current_function
from ...cpu_core.nir_fold.repeated_sums import (
    Entry,
    call_step,
    chain_params,
    chain_step,
    indexed_loop,
    later_entry,
    param_step,
    sum_entry,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .state import TranspilerState


def slot_code(tr: TranspilerState, own: tuple) -> str:
    """The index of a chain parameter's write's first constant (:func:`param_step`) among the
    constants the caller passed: its slot, plus the stride times the loop's pass."""
    _, at, stride, loop, _ = own
    if loop is None:
        return str(at)
    return f"{at} + {stride} * {tr.fold_state.sum_index[id(loop)]}"


def repeated_sum(tr: TranspilerState, e: A.Assignment, mask: str | None, old: str) -> str | None:
    """The code of the new value of a step of a chain: ``base + K`` in llvmpipe mode (K
    :func:`chain_plan`'s), the written ``old + c`` otherwise; None for any other write. The
    first step of a chain keeps the value before it (`old`) in a temporary."""
    step = chain_step(tr, e)
    if step is None or tr.fn is None:
        return None
    sign, k_node = step
    tk = tr.expr(k_node, mask)
    written = tr.binary_values(sign, tr.type_of(e.target), tr.type_of(k_node), old, tk)
    later = later_entry(tr, e)
    first = _step_code(tr, e, sum_entry(tr, e), old, written)
    if later is None:
        return first
    rest = _step_code(tr, e, later[1], old, written, own=False)
    return f"(({first or written}) if {tr.fold_state.sum_index[id(later[0])]} == 0 else {rest})"


def _step_code(
    tr: TranspilerState, e: Any, entry: Entry | None, old: str, written: str, own: bool = True
) -> str | None:
    """A step's ``base + K`` from a chain parameter's caller (`own`) or from `entry`."""
    mine = param_step(tr, e) if own else None
    if mine is not None:  # (a chain parameter: the caller's base and K, or None)
        b, k = f"_cb{mine[0]}", f"_ck{mine[0]}"
        return f"(({b} + {k}[{slot_code(tr, mine)}]) if rt.lp and {k} is not None else {written})"
    base = _base(tr, entry, old)
    if entry is None or base is None:
        return None if own else written
    k = _k_code(tr, entry, [_vector(tr, ks) for ks in entry.ks])
    return f"(({base} + {k}) if rt.lp else {written})"


def _base(tr: TranspilerState, entry: Entry | None, old: str | None) -> str | None:
    """The code of the value before the entry's chain: kept in a temporary at its first write
    (`old`: the value there), read in the same Python function after it."""
    if entry is None:
        return None
    bases = tr.fold_state.sum_chains
    key = (id(current_function(tr).sym), entry.chain, id(entry.sym))
    if entry.root and old is not None:
        bases[key] = (tr.tmp(old), tr.lines)
    known = bases.get(key)
    return known[0] if known is not None and known[1] is tr.lines else None


def _vector(tr: TranspilerState, ks: list) -> str:
    codes = [tr.const_float(float(k)) for k in ks]
    return codes[0] if len(codes) == 1 else tr.vector(codes)


def _k_code(tr: TranspilerState, entry: Entry, codes: list[str]) -> str:
    """One code per copy: the copy's, indexed by the unrolled loop's pass when they differ."""
    if len(codes) == 1:
        return codes[0]
    return f"({', '.join(codes)})[{tr.fold_state.sum_index[id(entry.loop)]}]"


def chain_call_args(
    tr: TranspilerState, call: A.Call, fn: Symbol, args: dict[int, str]
) -> list[str]:
    """The chain arguments of a call of `fn`, two per :func:`chain_params` parameter, in
    order: the base and ``(K1, K2, ...)`` where the call continues or starts a chain of the
    caller (or passes on the caller's own chain parameter), None and None where it does not
    (the callee computes as written). `args`: the code of each inout argument's value."""
    later = later_entry(tr, call)
    first = _call_args(tr, call, fn, args, sum_entry(tr, call), True)
    if later is None:
        return first
    rest = _call_args(tr, call, fn, args, later[1], False)
    ix = tr.fold_state.sum_index[id(later[0])]
    return [f"({a} if {ix} == 0 else {b})" for a, b in zip(first, rest)]


def _call_args(
    tr: TranspilerState,
    call: A.Call,
    fn: Symbol,
    args: dict[int, str],
    entry: Entry | None,
    own_chain: bool,
) -> list[str]:
    out = []
    for i in sorted(chain_params(tr, fn)):
        step = call_step(tr, call)
        mine = step is not None and step[0] == i
        own = param_step(tr, call) if mine and own_chain else None
        if own is not None:
            j, a, n = own[0], slot_code(tr, own), own[4]
            out += [f"_cb{j}", f"(None if _ck{j} is None else _ck{j}[{a}:{a} + {n}])"]
            continue
        base = _base(tr, entry, args.get(i)) if mine else None
        if entry is None or base is None:
            out += ["None", "None"]
            continue
        tuples = [f"({''.join(tr.const_float(float(k)) + ', ' for k in ks)})" for ks in entry.ks]
        out += [base, _k_code(tr, entry, tuples)]
    return out


def chain_param_names(tr: TranspilerState, fn: Symbol) -> list[str]:
    """The extra parameters of a function with :func:`chain_params`: the base and the
    constants of the caller's chain through each (:func:`chain_call_args`)."""
    return [f"_c{x}{i}" for i in sorted(chain_params(tr, fn)) for x in "bk"]


def enter_unrolled(tr: TranspilerState, loop: Any) -> None:
    """Before an unrolled loop of the plan: the value before a chain that starts there, kept,
    the temporaries loop_copies.later_values names, and a count of its passes where its steps'
    constants (or a merge: loop_copies.merging_loop) differ from copy to copy."""
    entry = sum_entry(tr, loop)
    if entry is not None and entry.root:
        _base(tr, entry, tr.var_name(entry.sym, entry.sym.node))
    for value, sym in later_values(tr, loop):  # (a temporary a later copy merges into)
        tr.fold_state.kept_slots[id(value)] = (tr.tmp(tr.var_name(sym, sym.node)), tr.lines)
    if indexed_loop(tr, loop):
        name = tr.fresh("ix")
        fn = tr.fn
        assert fn is not None  # (emitting a function)
        fn.defined.remove(name)  # (a pass count, no lane value)
        tr.emit(f"{name} = 0")
        tr.fold_state.sum_index[id(loop)] = name


def end_of_unrolled_body(tr: TranspilerState, loop: Any) -> None:
    """At the end of an unrolled loop's body: its pass count advanced (:func:`enter_unrolled`)."""
    name = tr.fold_state.sum_index.get(id(loop))
    if name is not None:
        tr.emit(f"{name} += 1")
