"""A variable advanced by constants: ``seed += 0.1`` written again and again (path tracers'
random numbers).

NIR is SSA: ``seed += 0.1; seed += 0.1; seed += 0.1`` is ``((s0 + 0.1) + 0.1) + 0.1``, and
``('~fadd', '#a', ('fadd', 'b(is_not_const)', '#c')) -> (a + c) + b`` folds each new constant
into the sum before it, in float32, left to right: ``s0 + ((0.1 + 0.1) + 0.1)`` (measured on
llvmpipe, tests/gl/test_llvmpipe_repeated_sums.py). The chain runs while each step's previous
write reaches it alone (analysis.dataflow: it runs before on every path, nothing writes the
variable in between), so it restarts at a loop top and stops at the join after a branch that
writes the variable (a phi to NIR). The generated code has one variable per GLSL one, so the
value before the chain is kept in a temporary (:func:`repeated_sum`).

NIR inlines every call first, so the chain runs through a call that passes the variable to an
``inout`` parameter its callee only advances by constants (:func:`chain_params`: ``float
rnd(inout float s) { s += 0.1; return s; }`` called three times is ``s0 + ((0.1 + 0.1) +
0.1)``, measured). Such a callee takes the caller's chain as one more argument per parameter,
``(base, pre, merged)``: its steps compute ``base + ((merged + c) + pre)``, and a caller with no
chain passes ``(value, 0, 0)``, which gives the written ``value + c`` (``0 + c`` is c).

NIR unrolls a loop of a constant count (:func:`unrolled_chain`), and the copies continue the
chain, but not left to right from the constant before the loop: the loop's own constants are
summed first and the one before the loop (``pre``) added to that sum, ``s0 + ((c + c) + p)``
in the second copy of ``p; for (4) { += c }`` (measured, with the constants after the loop
added left to right after it). Followed only where the body adds one constant an iteration (a
step, or a call of a callee that adds one): with two or more, the measured orders (the body's
constants summed right to left first, the values inside the body in yet another order) are not
copied, and the chain restarts at the loop top as for a loop NIR keeps."""

from __future__ import annotations

from typing import Any

from .....frontend import syntax as A
from .....semantics.analysis.dataflow import FunctionFacts, written_variable
from .....semantics.model import Symbol
from .queries import current_function, function_facts, is_constant, is_varying
from .return_register import unrolled

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..state import FoldEngine, TranspilerState


def sum_step(tr: FoldEngine, e: Any) -> tuple[str, Any, Any, bool] | None:
    """(sign, the constant, the previous step or None, whether a later step continues this
    one and its value before must be kept) for a step ``x += #c`` (``x -= #c``, ``x = x +
    #c``, ``x = #c + x``, ``x = x - #c``); None for any other write. Emits nothing: both CPU
    engines ask it."""
    step = _step(tr, e)
    if step is None:
        return None
    sym = tr.model.symbol_of(e.target)
    prev = _previous_step(tr, e, sym)
    kept = prev is None and id(e) in _chained(tr) and _varying_start(tr, e, sym)
    return step[0], step[1], prev, kept


def repeated_sum(tr: TranspilerState, e: A.Assignment, mask: str | None, old: str) -> str | None:
    """The code of the new value of a step (:func:`sum_step`) whose previous write is a step
    too: ``base + (c1 + c2 ...)`` in llvmpipe mode, the written ``old + c`` otherwise; None
    for any other write. The first step of a chain keeps the value before it (`old`) in a
    temporary and returns None."""
    step = sum_step(tr, e)
    if step is None:
        return None
    sign, k_node, prev, kept = step
    tk = tr.expr(k_node, mask)
    k = f"(-{tk})" if sign == "-" else tk
    chains = tr.fold_state.sum_chains
    known = chains.get(id(prev)) if prev is not None else None
    if known is None or known[3] is not tr.lines:
        if kept:
            chains[id(e)] = (tr.tmp(old), None, k, tr.lines)
        return None
    base, pre, merged, _ = known
    merged = k if merged is None else f"({merged} + {k})"
    chains[id(e)] = (base, pre, merged, tr.lines)
    t = tr.type_of(e.target)
    written = tr.binary_values(sign, t, tr.type_of(k_node), old, tk)
    return f"(({base} + {_total(pre, merged)}) if rt.lp else {written})"


def _total(pre: str | None, merged: str) -> str:
    """The code of a chain's constant: the merged one, plus the one before an unrolled loop."""
    return merged if pre is None else f"({merged} + {pre})"


def _step(tr: FoldEngine, e: Any) -> tuple[str, Any] | None:
    """("+" or "-", the constant) when `e` adds a float constant to a whole local or parameter
    and stores the sum back in it; else None."""
    if not isinstance(e, A.Assignment) or not isinstance(e.target, A.Identifier):
        return None
    sym = tr.model.symbol_of(e.target)
    t = tr.type_of(e.target)
    if sym is None or sym.kind not in ("local", "param") or t.base != "float" or t.is_matrix:
        return None
    if e.op in ("+=", "-="):
        sign, k_node = e.op[0], e.value
    elif e.op == "=" and isinstance(e.value, A.Binary) and e.value.op in ("+", "-"):
        left, right = e.value.left, e.value.right
        if _reads(tr, left, sym) and is_constant(tr, right):
            sign, k_node = e.value.op, right
        elif e.value.op == "+" and _reads(tr, right, sym) and is_constant(tr, left):
            sign, k_node = "+", left
        else:
            return None
    else:
        return None
    kt = tr.type_of(k_node)
    if not is_constant(tr, k_node) or kt.base != "float" or not (kt.is_scalar or kt == t):
        return None
    return sign, k_node


def _reads(tr: FoldEngine, node: Any, sym: Any) -> bool:
    return isinstance(node, A.Identifier) and tr.model.symbol_of(node) is sym


def _previous_step(tr: FoldEngine, e: Any, sym: Any) -> Any:
    """The step (or call of a :func:`chain_params` callee) whose value of `sym` alone reaches
    `e` (NIR sees it as e's operand); the parameter's node at the first write of a chain
    parameter of the function being emitted (the caller's chain comes in there); the loop at
    the write in the body of an unrolled loop that advances `sym` (:func:`unrolled_chain`);
    else None."""
    facts = function_facts(tr)
    if not facts.ok or id(e) not in facts.enter:
        return None  # (a node of an inlined body: another function's)
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(e)]]
    loops = [lp for lp in facts.enclosing_loops(e) if unrolled_chain(tr, lp, sym)]
    if loops and not any(facts.contains(loops[-1].body, w.node) for w in before):
        return loops[-1]  # (the first write of the body: its chain starts at the loop's phi)
    if not before:
        fn = current_function(tr).sym
        params = chain_params(tr, fn) if fn is not None else {}
        index = [i for i, p in enumerate(fn.node.proto.params) if tr.model.symbol_of(p) is sym]
        return fn.node.proto.params[index[0]] if index and index[0] in params else None
    w = before[-1]
    if not _is_step(tr, w.node, sym) or not facts.dominates(w.node, e):
        return None
    if facts.written_between(w.node, e, [sym]):
        return None
    return w.node


def _is_step(tr: FoldEngine, node: Any, sym: Any) -> bool:
    if isinstance(node, A.Call):
        return call_step(tr, node) is not None and call_step(tr, node)[1] is sym
    return _step(tr, node) is not None


def call_step(tr: FoldEngine, call: A.Call) -> tuple[int, Any, list[float]] | None:
    """(the parameter's index, the caller's variable, the constants the callee adds to it in
    order, signed) for a call that passes a whole float variable to a :func:`chain_params`
    parameter; None for any other call (or one with two such parameters)."""
    target = tr.model.call_target(call)
    if not isinstance(target, Symbol):
        return None
    params = chain_params(tr, target)
    found = []
    for i, ks in params.items():
        sym, whole = written_variable(tr.model, call.args[i])
        if (
            sym is not None
            and whole
            and isinstance(call.args[i], A.Identifier)
            and sym.kind in ("local", "param")
        ):
            found.append((i, sym, ks))
    return found[0] if len(found) == 1 else None


def chain_params(tr: FoldEngine, fn: Symbol) -> dict[int, list[float]]:
    """index -> the constants (signed, in order) for each ``inout float`` parameter of user
    function `fn` that it only advances by constants, in steps or calls of such functions, all
    in its body's straight line (no branch, loop or return before its end around them): NIR
    inlines the call and the caller's chain runs through it."""
    cache = tr.fold_state.sum_params
    if id(fn) in cache:
        return cache[id(fn)]
    cache[id(fn)] = {}  # (GLSL has no recursion: a guard only)
    facts = _facts_of(tr, fn)
    body = fn.node.body.stmts
    if not facts.ok or any(
        isinstance(n, A.Discard) or isinstance(n, A.Return) and (not body or n is not body[-1])
        for n in fn.node.body.walk()
    ):
        return cache[id(fn)]
    out: dict[int, list[float]] = {}
    for i, (p, (_, ptype, d)) in enumerate(zip(fn.node.proto.params, fn.params)):
        psym = tr.model.symbol_of(p)
        if d != "inout" or psym is None or ptype.base != "float" or not ptype.is_scalar:
            continue
        ks: list[float] | None = []
        for w in facts.writes_to(psym):
            if facts.region[id(w.node)] != () or facts.is_dead(w.node) or ks is None:
                ks = None
                break
            step = _step(tr, w.node) if isinstance(w.node, A.Assignment) else None
            inner = call_step(tr, w.node) if isinstance(w.node, A.Call) else None
            if step is not None:
                v = float(tr.model.const_value(step[1]))
                ks.append(-v if step[0] == "-" else v)
            elif inner is not None and inner[1] is psym:
                ks += inner[2]
            else:
                ks = None
        if ks:
            out[i] = ks
    cache[id(fn)] = out
    return out


def unrolled_chain(tr: FoldEngine, loop: Any, sym: Any) -> bool:
    """`loop` is one NIR unrolls (a ``for`` of a constant count, :func:`unrolled`, with no
    jump and no loop in its body) and its body advances `sym` by one constant, in a step or a
    call in its straight line: each copy continues the chain of the one before."""
    cache = tr.fold_state.sum_loops
    key = (id(loop), id(sym))
    if key not in cache:
        cache[key] = False
        facts = function_facts(tr)
        if unrolled(tr, loop) and not any(
            isinstance(n, (A.Break, A.Continue, A.Return, A.Discard, A.For, A.While, A.DoWhile))
            for n in loop.body.walk()
        ):
            inner = facts.region[id(loop.body)]
            writes = [w for w in facts.writes_to(sym) if facts.contains(loop.body, w.node)]
            if len(writes) == 1 and facts.region[id(writes[0].node)] == inner:
                node = writes[0].node
                step = call_step(tr, node) if isinstance(node, A.Call) else None
                cache[key] = (
                    _step(tr, node) is not None
                    if isinstance(node, A.Assignment)
                    else step is not None and step[1] is sym and len(step[2]) == 1
                )
    return cache[key]


def loop_chain(tr: FoldEngine, loop: Any) -> list[tuple[Any, Any]]:
    """(the variable, the last write of the body) for each float local or parameter whose
    chain an unrolled loop continues (:func:`unrolled_chain`)."""
    facts = function_facts(tr)
    if not facts.ok or id(loop) not in facts.enter:
        return []
    out = []
    for ws in facts.writes.values():
        inside = [w for w in ws if facts.contains(loop.body, w.node)]
        sym = ws[0].symbol
        if inside and sym.kind in ("local", "param") and unrolled_chain(tr, loop, sym):
            out.append((sym, inside[-1].node))
    return out


def _facts_of(tr: FoldEngine, fn: Symbol) -> Any:
    cache = tr.fold_state.fn_facts
    if id(fn) not in cache:
        cache[id(fn)] = FunctionFacts(fn.node, tr.model)
    return cache[id(fn)]


def _chained(tr: FoldEngine) -> set[int]:
    """ids of the steps of the current function that a later step continues."""
    cache = tr.fold_state.sum_chained
    key = id(current_function(tr).sym)
    if key not in cache:
        out: set[int] = set()
        body = current_function(tr).sym.node.body
        for n in body.walk():
            if isinstance(n, A.Assignment) and _step(tr, n) is not None:
                prev = _previous_step(tr, n, tr.model.symbol_of(n.target))
            elif isinstance(n, A.Call) and call_step(tr, n) is not None:
                prev = _previous_step(tr, n, call_step(tr, n)[1])
            elif isinstance(n, A.For):
                for sym, _ in loop_chain(tr, n):
                    prev = _previous_step(tr, n, sym)
                    if prev is not None:
                        out.add(id(prev))
                continue
            else:
                continue
            if prev is not None:
                out.add(id(prev))
        cache[key] = out
    return cache[key]


def _varying_start(tr: FoldEngine, e: Any, sym: Any) -> bool:
    """The value before the chain is no constant to NIR (``b(is_not_const)``: a constant is
    folded step by step instead)."""
    facts = function_facts(tr)
    before = [w for w in facts.writes_to(sym) if w.pos < facts.enter[id(e)]]
    if not before:
        return sym.kind == "param"
    w = before[-1]
    if w.kind in ("=", "init") and w.value is not None and facts.dominates(w.node, e):
        return is_varying(tr, w.value)
    return True


def chain_before(tr: FoldEngine, node: Any, sym: Any) -> Any:
    """The node whose chain of `sym` reaches `node` (a call or a loop: :func:`_previous_step`),
    else None; and whether a chain may start there (the value before is no constant)."""
    return _previous_step(tr, node, sym)


def varying_start(tr: FoldEngine, node: Any, sym: Any) -> bool:
    """The value of `sym` before `node` is no constant to NIR (a chain may start there)."""
    return _varying_start(tr, node, sym)


def chain_call_args(
    tr: TranspilerState, call: A.Call, fn: Symbol, args: dict[int, str]
) -> list[str]:
    """The chain arguments of a call of `fn` (one per :func:`chain_params` parameter, in order:
    ``(base, pre, merged)``), the caller's chain where the call continues one, else ``(value,
    0, 0)``; `args`: the code of each inout argument's value by index. Records the chain the
    call leaves for the steps after it."""
    params = chain_params(tr, fn)
    if not params:
        return []
    zero = tr.const_float(0.0)
    step = call_step(tr, call)
    out = []
    for i in sorted(params):
        if step is None or step[0] != i:
            out.append(f"({args[i]}, {zero}, {zero})")
            continue
        chains = tr.fold_state.sum_chains
        prev = _previous_step(tr, call, step[1])
        known = chains.get(id(prev)) if prev is not None else None
        if known is None or known[3] is not tr.lines:
            base, pre, merged = args[i], None, None
        else:
            base, pre, merged = known[:3]
        out.append(f"({base}, {pre or zero}, {merged or zero})")
        if known is not None or _varying_start(tr, call, step[1]):
            for k in step[2]:
                c = tr.const_float(k)
                merged = c if merged is None else f"({merged} + {c})"
            chains[id(call)] = (base, pre, merged, tr.lines)
    return out


def chain_param_names(tr: TranspilerState, fn: Symbol) -> list[str]:
    """The extra parameters of a function with :func:`chain_params` (the caller's chain of each,
    :func:`chain_call_args`), registered as the chains its first steps continue."""
    names = []
    for i in sorted(chain_params(tr, fn)):
        name = f"_c{i}"
        names.append(name)
        node = fn.node.proto.params[i]
        tr.fold_state.sum_chains[id(node)] = (f"{name}[0]", f"{name}[1]", f"{name}[2]", tr.lines)
    return names


def enter_unrolled(tr: TranspilerState, loop: Any) -> None:
    """Before an unrolled loop that continues a chain (:func:`loop_chain`): a variable for the
    sum of the loop's own constants (0 before the first copy), the chain its body's step
    continues, with the constant before the loop as its ``pre``."""
    chains = tr.fold_state.sum_chains
    for sym, _ in loop_chain(tr, loop):
        prev = _previous_step(tr, loop, sym)
        known = chains.get(id(prev)) if prev is not None else None
        if known is not None and known[3] is tr.lines:
            base, pre = known[0], tr.tmp(_total(known[1], known[2]))
        elif _varying_start(tr, loop, sym):
            base, pre = tr.tmp(tr.var_name(sym, sym.node)), None
        else:
            continue
        acc = tr.fresh("ka")
        tr.emit(f"{acc} = {tr.const_float(0.0)}")
        chains[id(loop)] = (base, pre, acc, tr.lines)


def end_of_unrolled_body(tr: TranspilerState, loop: Any) -> None:
    """At the end of an unrolled loop's body: the loop's sum advanced by the iteration's
    constant (:func:`enter_unrolled`)."""
    chains = tr.fold_state.sum_chains
    for _, last in loop_chain(tr, loop):
        start, end = chains.get(id(loop)), chains.get(id(last))
        if start is None or end is None or end[3] is not tr.lines or end[1] is not start[1]:
            continue
        tr.emit(f"{start[2]} = {end[2]}")
