"""A call folded per call site, written by the NumPy transpiler: the terms cpu_core/call_fold.py
evaluates (`fold_plan`: constants propagated into the callee as NIR does after inlining) as
Python temporaries, under ``if rt.lp:``, and the call as written under ``else:``."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ....semantics.model import Symbol
from ...cpu_core.call_fold import fold_plan, opaque_calls, record_sums
from ...cpu_core.fold_eval import member_size
from ...cpu_core.nir_fold.repeated_sums import chain_params

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .state import TranspilerState


def folded_call(tr: TranspilerState, call: A.Call, fn: Symbol, mask: str | None) -> str | None:
    """The code of the call `call` of user function `fn` with constants propagated as NIR does
    (cpu_core/call_fold.py), emitted as ``if rt.lp: <folded> else: <the call as written>``;
    None where :func:`fold_plan` leaves the call as written."""
    if tr.watched is not None:
        return None
    plan = fold_plan(tr, call, fn, mask, lambda f: bool(chain_params(tr, f)))
    return None if plan is None else _emit_call(tr, call, fn, mask, *plan)


def _emit_call(
    tr: TranspilerState,
    call: A.Call,
    fn: Symbol,
    mask: str | None,
    env: dict[int, list],
    params: list[Any],
    result: list[Any],
    holders: list[tuple[int, Any]],
) -> str:
    r = tr.fresh("t")
    # (the terms read the globals' known values: the call as written writes them, unless the
    # writes are the callee's calls made in the folded code: cpu_core.call_fold.opaque_calls)
    effects = tr.facts.writes_globals(fn) and not opaque_calls(call, holders)
    if effects:
        names = {i: tr.tmp(tr.expr(a, mask)) for i, a in holders}
        tr.emit(f"{r} = {_written_call(tr, call, fn, mask)}")
    tr.emit("if rt.lp:  # constants propagated into the call as NIR does (transpile/call_fold.py)")
    tr.indent += 1
    if not effects:
        names = {i: tr.tmp(tr.expr(a, mask)) for i, a in holders}
    memo: dict[int, str] = {}

    def code(t: Any) -> str:
        if id(t) in memo:
            return memo[id(t)]
        if t.op == "k" and t.value is not None:
            c = tr.const_float(t.value)
        elif t.op == "x":
            c = t.code
            for i, name in names.items():
                c = c.replace(f"@{i}@", name)
        else:
            parts = [code(x) for x in t.args]
            if t.op == "neg":
                c = tr.tmp(f"(-{parts[0]})")
            elif t.op == "call":
                c = tr.tmp(
                    f"rt.{t.code.format(*parts)}"
                    if "{" in t.code
                    else f"rt.{t.code}({', '.join(parts)})"
                )
            else:
                c = tr.tmp(f"({parts[0]} {t.op} {parts[1]})")
        memo[id(t)] = c
        return c

    def value(terms: list[Any], t: Any) -> str:
        if t.is_struct:  # (members one after the other, as call_fold evaluates them)
            fields, at = [], 0
            for fname, ft in t.fields:
                width = member_size(ft)
                fields.append(f"{tr.member(fname, call)}={value(terms[at : at + width], ft)}")
                at += width
            return f'rt.struct("{tr.struct_name(t)}", {", ".join(fields)})'
        cs = [code(x) for x in terms]
        if t.is_scalar:
            return cs[0]
        if t.is_vector:
            return f"rt.vec({t.size}, {', '.join(cs)})"
        return f"rt.mat({t.cols}, {t.rows}, {', '.join(cs)})"

    for a, p, (_, _, dr) in zip(call.args, params, fn.params):
        if dr != "in":
            tr.write(tr.lvalue(a, mask), value(env[id(p)], tr.type_of(a)), mask)
            record_sums(tr, call, a, env[id(p)], memo)
    tr.emit(f"{r} = {value(result, tr.type_of(call)) if result else 'None'}")
    tr.indent -= 1
    if not effects:
        tr.emit("else:")
        tr.indent += 1
        tr.emit(f"{r} = {_written_call(tr, call, fn, mask)}")
        tr.indent -= 1
    return r


def _written_call(tr: TranspilerState, call: A.Call, fn: Symbol, mask: str | None) -> str:
    """The code of the call as written (its value)."""
    tr.fold_state.call_fold_off = True
    try:
        return tr.user_call(call, fn, mask)
    finally:
        tr.fold_state.call_fold_off = False
