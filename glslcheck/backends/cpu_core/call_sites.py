"""Where a call reads a local of its caller: whether a local's initializer, evaluated again at
the call, gives the local's value there, and which of its components a statement writes
(for cpu_core/call_fold.py, which follows a call's constant components through such locals:
its module doc)."""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...semantics.analysis import param_directions
from ...semantics.model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .fold_protocols import FoldEmitter


def unchanged_init(tr: FoldEmitter, ident: A.Identifier, call: A.Call) -> Any:
    """The initializer of the local `ident` when it is declared by a top-level statement of the
    current function before the one that holds `call`, and neither it nor a local or parameter
    the initializer reads is written in between (so the initializer, evaluated again at the
    call, gives its value); else None."""
    sym = tr.model.symbol_of(ident)
    places = top_level_places(tr, sym, call)
    if places is None or places[1] >= places[2]:
        return None
    stmts, decl, at = places
    assert sym is not None and isinstance(sym.node, A.Declarator) and sym.node.init is not None
    init = sym.node.init
    named = {sym} | {tr.model.symbol_of(n) for n in init.walk() if isinstance(n, A.Identifier)}
    read = [r for r in named if r is not None and r.kind in ("local", "param")]
    for st in stmts[decl + 1 : at + 1]:
        for n in st.walk():
            if any(written_components(tr, n, r, call) for r in read):
                return None
    return init


def local_initializer(sym: Symbol | None) -> Any:
    """The initializer of a local variable declared with one (`float k = 5.0;`), else None."""
    if sym is None or sym.kind != "local" or not isinstance(sym.node, A.Declarator):
        return None
    return sym.node.init


def top_level_places(
    tr: FoldEmitter, sym: Symbol | None, call: A.Call
) -> tuple[list, int, int] | None:
    """(the current function's top-level statements, the index of the declaration statement
    of the local `sym`, the index of the statement holding `call`) when `sym` is a local with
    an initializer declared by a top-level statement; else None."""
    if local_initializer(sym) is None:
        return None
    assert sym is not None and tr.fn is not None  # folding a call inside a function
    stmts = tr.fn.sym.node.body.stmts
    decl = next((i for i, st in enumerate(stmts) if any(n is sym.node for n in st.walk())), None)
    at = next((i for i, st in enumerate(stmts) if any(n is call for n in st.walk())), None)
    if decl is None or at is None or not isinstance(stmts[decl], A.DeclarationStatement):
        return None
    return stmts, decl, at


def written_components(tr: FoldEmitter, n: Any, sym: Symbol, call: A.Call) -> Any:
    """The components of `sym` the node `n` writes: "all", a tuple of indices, or ()."""
    targets: list[Any] = []
    if isinstance(n, A.Assignment):
        targets.append(n.target)
    elif isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
        targets.append(n.operand)
    elif isinstance(n, A.Call) and n is not call:
        tgt = tr.model.call_target(n)
        if isinstance(tgt, Symbol):
            targets += [a for a, d in zip(n.args, param_directions(tgt)) if d != "in"]
        elif n.callee == "modf" and len(n.args) == 2:
            targets.append(n.args[1])
    for x in targets:
        root = x
        while isinstance(root, (A.Field, A.Index)):
            root = root.base
        if isinstance(root, A.Identifier) and tr.model.symbol_of(root) is sym:
            if isinstance(x, A.Field) and x.base is root and tr.model.is_swizzle(x):
                return tuple(tr.model.swizzle_indices(x))  # (a struct's member: "all" below)
            return "all"
    return ()


def struct_source(tr: FoldEmitter, a: Any, call: A.Call) -> A.Call | None:
    """The call of a user function that initialises the struct local `a`, where evaluating it
    again at `call` gives a's value there: `a` declared by a top-level statement before the one
    that holds `call`, and neither it nor a local or parameter the initializer reads written
    in between, no global read but constants and uniforms (a call may write a global); else
    None."""
    init = unchanged_init(tr, a, call) if isinstance(a, A.Identifier) else None
    if not (
        isinstance(init, A.Call)
        and not init.constructor
        and isinstance(tr.model.call_target(init), Symbol)
        and not any(tr.has_effects(x) for x in init.args)
    ):
        return None
    for n in init.walk():
        sym = tr.model.symbol_of(n) if isinstance(n, A.Identifier) else None
        if sym is not None and sym.kind not in ("local", "param", "uniform"):
            if tr.model.const_value(n) is None:
                return None
    return init
