"""A variable advanced by constants: ``seed += 0.1`` written again and again (path tracers'
random numbers), through the calls NIR inlines and the loops it unrolls.

NIR is SSA: ``seed += 0.1; seed += 0.1; seed += 0.1`` is ``((s0 + 0.1) + 0.1) + 0.1``, and
``('~fadd', '#a', ('fadd', 'b(is_not_const)', '#c')) -> (a + c) + b`` merges the constants
into one, ``s0 + K``, in an order sum_order.py simulates (not simply left to right). A chain
runs while each step's previous write reaches it alone (analysis.dataflow: it runs before on
every path, nothing writes the variable in between), so it restarts at the top of a loop NIR
keeps and after the join of a branch that writes the variable (a phi to NIR), and not from a
constant (NIR folds those step by step, as written). It runs into either arm of an ``if`` (a
write there adds to the value from before the ``if``) and past an arm that ends in a
``return`` (what follows is the other arm to NIR).

NIR inlines every call first, so a chain runs through a call that passes the variable (a
local or a global) to an ``inout`` parameter, or a global the callee writes, that the callee
only advances by constants (:func:`chain_params`: ``float rnd(inout float s) { s += 0.1;
return s; }``, a path tracer's ``float seed;`` advanced in ``hash2()`` or passed as
``hash2(seed)``). It unrolls a ``for`` of a constant count and a small body after one pass of
the rules over the body (:func:`unrolled_chain`, loop_unroll.py), so the copies continue it; a
loop left early ends in a phi, and so does a two-pass loop whose branch NIR folds in the first
copy only, the second copy's branch continuing the first copy's chain (:func:`folded_branch`).
A body that writes the variable in arms NIR keeps continues it in the first copy only, each
later copy starting from the phi of the arms before (:func:`first_copy_loop`; the later
passes' plan: :func:`later_entry`). A callee that writes it in arms continues the caller's
chain in each arm, and the chain restarts after the call (the join's phi).

:func:`chain_plan` builds each chain of a function (steps, calls spread into their callees'
programs, unrolled loops) and asks sum_order.py for K at every step, per copy of an unrolled
loop. The engines emit ``base + K`` in llvmpipe mode from the plan (the NumPy backend:
numpy_engine/transpile/sum_chains.py; the compiled engine: its expressions.py): the value
before the chain kept in a temporary, K a constant, or a loop's constants indexed by its pass;
a callee's step reads its K from two more arguments per chain variable, the caller's base and
its constants ``(K1, K2, ...)``, or None (no chain: the written order)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ....frontend import syntax as A
from ....semantics.analysis import FunctionFacts, written_variable
from ....semantics.model import Symbol
from .loop_copies import merging_loop
from .loop_unroll import nir_unrolls, trip_count
from .queries import (
    FunctionStandin,
    asked_in,
    constant_value,
    current_function,
    function_facts,
    is_constant,
    is_varying,
)
from .ray_dots import ray_loop
from .sum_order import Loop, Step, chain_constants

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..fold_protocols import FoldEngine


class Entry:
    """A write of a chain in the plan of a function: its chain (a number), whether it is the
    chain's first (the value before it is the base), the K of its value for each copy of the
    unrolled `loop` around it (one copy outside; a step: one K per component, a call: one per
    step of its callee) and the written variable."""

    __slots__ = ("chain", "root", "ks", "loop", "sym")

    def __init__(self, chain: int, root: bool, ks: list, loop: Any, sym: Any) -> None:
        self.chain, self.root, self.ks, self.loop, self.sym = chain, root, ks, loop, sym


def chain_step(tr: FoldEngine, e: Any) -> tuple[str, Any] | None:
    """("+" or "-", the constant) when `e` adds a float constant to a whole local, parameter or
    global variable and stores the sum back in it; else None."""
    if not isinstance(e, A.Assignment) or not isinstance(e.target, A.Identifier):
        return None
    sym = tr.model.symbol_of(e.target)
    t = tr.type_of(e.target)
    if not _variable(sym) or t.base != "float" or t.is_matrix:
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


def _variable(sym: Any) -> bool:
    """A variable a chain may advance: a local, a parameter, a global the shader writes."""
    return sym is not None and (
        sym.kind in ("local", "param") or sym.kind == "global" and sym.qualifier is None
    )


class _CallWrite:
    """A call of a user function that writes a global (what analysis.dataflow's Write is for a
    direct write: its position is the call's exit)."""

    __slots__ = ("symbol", "pos", "kind", "value", "node")

    def __init__(self, symbol: Any, pos: int, node: Any) -> None:
        self.symbol, self.pos, self.kind, self.value, self.node = symbol, pos, "out", None, node


def _writes(tr: FoldEngine, facts: Any, sym: Any) -> list:
    """The writes of `sym` in the function of `facts`, in order; for a global, also the calls of
    user functions that write it (NIR inlines them: its chain runs through)."""
    ws = facts.writes_to(sym)
    if sym.kind != "global":
        return ws
    calls = [
        _CallWrite(sym, facts.exit[id(c)], c)
        for c in facts.calls
        if isinstance(tr.model.call_target(c), Symbol)
        and _writes_global(tr, tr.model.call_target(c), sym)
    ]
    return sorted(list(ws) + calls, key=lambda w: w.pos)


def _writes_global(tr: FoldEngine, fn: Symbol, sym: Any) -> bool:
    """User function `fn` writes the global `sym`, itself or through the functions it calls."""
    cache = tr.fold_state.sum_global_writers
    key = (id(fn), id(sym))
    if key not in cache:
        cache[key] = False  # (GLSL has no recursion: a guard only)
        facts = _facts_of(tr, fn)
        cache[key] = bool(facts.writes_to(sym)) or any(
            isinstance(tr.model.call_target(c), Symbol)
            and _writes_global(tr, tr.model.call_target(c), sym)
            for c in facts.calls
        )
    return cache[key]


def _written_between(tr: FoldEngine, facts: Any, a: Any, b: Any, sym: Any) -> bool:
    """`sym` may be written after `a` and before `b` (analysis.dataflow's question; for a global
    only the calls that write it count, not every call), a write in the other arm of an ``if``
    `b` is in not counting (no path from it reaches `b` but through a loop, counted whole)."""
    spans = [(facts.exit[id(a)], facts.enter[id(b)])]
    around_a = {id(lp) for lp in facts.enclosing_loops(a)}
    for loop in facts.enclosing_loops(b):
        if id(loop) not in around_a:
            spans.append((facts.enter[id(loop)], facts.exit[id(loop)]))
    return any(
        lo < w.pos < hi and (i > 0 or not _cut_off(facts, w.node, b))
        for w in _writes(tr, facts, sym)
        for i, (lo, hi) in enumerate(spans)
    )


def _cut_off(facts: Any, a: Any, b: Any) -> bool:
    """No path runs `a` then `b` but through a loop: they are in the two arms of one ``if``,
    or `a` is in an arm of an ``if`` that ends in a ``return`` and `b` is outside that arm
    (NIR moves what follows such an ``if`` into its other arm)."""
    if _other_arm(facts, a, b):
        return True
    up = a
    while True:
        parent = facts.parent.get(id(up))
        if parent is None:
            return False
        if (
            isinstance(parent, A.If)
            and (up is parent.then or up is parent.else_)
            and _returns(up)
            and not facts.contains(up, b)
        ):
            return True
        up = parent


def _returns(arm: Any) -> bool:
    """The arm of an ``if`` always ends in a ``return``."""
    if isinstance(arm, A.Compound):
        return any(isinstance(x, A.Return) for x in arm.stmts)
    return isinstance(arm, A.Return)


def _other_arm(facts: Any, a: Any, b: Any) -> bool:
    """`a` and `b` are in the two arms of one ``if`` (or ``?:``): no path runs both."""
    ra, rb = facts.region[id(a)], facts.region[id(b)]
    for x, y in zip(ra, rb):
        if x != y:
            if x[0] != y[0] or {x[1], y[1]} != {0, 1}:
                return False
            up = facts.parent.get(id(a))
            while up is not None and id(up) != x[0]:
                up = facts.parent.get(id(up))
            return isinstance(up, (A.If, A.Ternary))
    return False


def _reads(tr: FoldEngine, node: Any, sym: Any) -> bool:
    return isinstance(node, A.Identifier) and tr.model.symbol_of(node) is sym


def _previous_step(tr: FoldEngine, e: Any, sym: Any) -> Any:
    """The step (or call of a :func:`chain_params` callee) whose value of `sym` alone reaches
    `e` (NIR sees it as e's operand); the parameter's node at the first write of a chain
    parameter of the function being emitted (the caller's chain comes in there); the loop at
    the first write of `sym` in the body of an unrolled loop (:func:`unrolled_chain`), and
    its body after such a loop that nothing leaves early; else None."""
    facts = function_facts(tr)
    if not facts.ok or id(e) not in facts.enter:
        return None  # (a node of an inlined body: another function's)
    before = [
        w
        for w in _writes(tr, facts, sym)
        if w.pos < facts.enter[id(e)] and not _cut_off(facts, w.node, e)
    ]
    loops = [lp for lp in facts.enclosing_loops(e) if _chained_loop(tr, lp, sym)]
    if loops and not any(facts.contains(loops[-1].body, w.node) for w in before):
        return loops[-1]  # (the first write of the body: its chain starts at the loop's phi)
    if not before:
        if tr.fold_state.sum_later:
            return None  # (the caller's chain parameter is not planned in later passes)
        fn = current_function(tr).sym
        index = [i for i, p in enumerate(fn.node.proto.params) if tr.model.symbol_of(p) is sym]
        if index and index[0] in chain_params(tr, fn):
            return fn.node.proto.params[index[0]]
        if sym.kind == "global" and _key(tr, sym) in chain_params(tr, fn):
            return sym.node  # (the caller's chain of the global comes in here)
        return None
    w = before[-1]
    left = [lp for lp in facts.enclosing_loops(w.node) if not facts.contains(lp, e)]
    if left:  # (the last write is in a loop `e` follows)
        loop = left[-1]
        if len(left) > 1 or not unrolled_chain(tr, loop, sym) or _phi_after(tr, loop, sym):
            return None
        if facts.dominates(loop, e) and not _written_between(tr, facts, loop, e, sym):
            return loop.body  # (after the loop: its last copy's value)
        return None
    if not _is_step(tr, w.node, sym) or not facts.dominates(w.node, e):
        return None
    if isinstance(w.node, A.Call) and _callee_program(tr, w.node).leaves:
        return None  # (the value after the call is a phi: a chain starts afresh from it)
    if _written_between(tr, facts, w.node, e, sym):
        return None
    return w.node


def _first_write(tr: FoldEngine, e: Any, sym: Any) -> bool:
    """No write of `sym` runs before `e` in its function (one in another arm of an ``if``
    around `e` does not)."""
    facts = function_facts(tr)
    return not any(
        w.pos < facts.enter[id(e)] and not _cut_off(facts, w.node, e)
        for w in _writes(tr, facts, sym)
    )


def _leaves(loop: Any) -> bool:
    """The loop can be left before its last pass (a break or a return in its body)."""
    return any(isinstance(n, (A.Break, A.Return)) for n in loop.body.walk())


def _is_step(tr: FoldEngine, node: Any, sym: Any) -> bool:
    if isinstance(node, A.Call):
        step = call_step(tr, node)
        return step is not None and step[1] is sym
    return isinstance(node, A.Assignment) and chain_step(tr, node) is not None


def _callee_program(tr: FoldEngine, call: A.Call) -> Program:
    """The callee's :class:`Program` of a call that advances a chain (:func:`call_step`)."""
    step = call_step(tr, call)
    assert step is not None
    return step[2]


def call_step(tr: FoldEngine, call: A.Call) -> tuple[int, Any, Program] | None:
    """(the parameter's index, the caller's variable, the callee's :class:`Program` for it) for
    a call that passes a whole float variable (a local, parameter or global: after inlining
    the parameter is a copy of it) to a :func:`chain_params` parameter, or whose callee
    advances a global; None for any other call (or one with two such chains). A global also
    passed to an ``out`` or ``inout`` parameter is the copy back at the return, not what the
    callee wrote to it."""
    target = tr.model.call_target(call)
    if not isinstance(target, Symbol):
        return None
    found = []
    copied_out = {
        id(written_variable(tr.model, a)[0])
        for a, (_, _, d) in zip(call.args, target.params)
        if d != "in"
    }
    for i, program in chain_params(tr, target).items():
        if i >= _GLOBALS:
            if id(_global_of(tr, i)) not in copied_out:
                found.append((i, _global_of(tr, i), program))
            continue
        sym, whole = written_variable(tr.model, call.args[i])
        if sym is not None and whole and isinstance(call.args[i], A.Identifier) and _variable(sym):
            found.append((i, sym, program))
    return found[0] if len(found) == 1 else None


class Program:
    """What a callee does to a chain parameter: its additions as sum_order ops (prev -1: the
    value the caller passes), where each write's ops are (id(write) -> (the unrolled loop
    around it or None, first op, how many)), and whether the value after the call is a phi
    (`leaves`: a loop it can leave early ends it, it writes in arms of an ``if``, or an arm
    ends in a ``return``): a chain of the caller restarts there."""

    __slots__ = ("ops", "where", "leaves")

    def __init__(self, ops: list, where: dict, leaves: bool) -> None:
        self.ops, self.where, self.leaves = ops, where, leaves

    def slots(self) -> int:
        """How many constants a caller passes: one per addition, per copy in a loop."""
        return sum(1 if isinstance(op, Step) else op.count * len(op.body) for op in self.ops)

    def slot(self, node: Any) -> tuple[int, int, Any, int]:
        """(the slot of the write's first constant in the first copy, the stride between two
        copies (0 outside a loop), the loop, how many constants the write adds a copy)."""
        loop, first, count = self.where[id(node)]
        at = 0
        for j, op in enumerate(self.ops):
            if loop is None and j == first:
                return at, 0, None, count
            if isinstance(op, Loop) and loop is not None and j == self.where[id(loop)][1]:
                return at + first, len(op.body), loop, count
            at += 1 if isinstance(op, Step) else op.count * len(op.body)
        raise AssertionError("a write of the program")


_GLOBALS = 1000  # chain_params' keys from here on are globals (_key), below parameters


def _key(tr: FoldEngine, sym: Any) -> int:
    """The chain_params key of a global: its number, in the order first asked, from _GLOBALS."""
    keys = tr.fold_state.sum_global_keys
    if id(sym) not in keys:
        keys[id(sym)] = (_GLOBALS + len(keys), sym)
    return keys[id(sym)][0]


def _global_of(tr: FoldEngine, key: int) -> Any:
    return next(sym for k, sym in tr.fold_state.sum_global_keys.values() if k == key)


def chain_params(tr: FoldEngine, fn: Symbol) -> dict[int, Program]:
    """index -> the :class:`Program` of each ``inout float`` parameter of user function `fn`
    that it only advances by constants (steps, calls of such functions), in its body's
    straight line or that of a loop NIR unrolls: NIR inlines the call and the caller's chain
    runs through it. A float global written so (itself or by the functions `fn` calls) is
    one too, under its :func:`_key`. The entry point has none: no user code calls it, and
    its globals start at their constant initializers (the chains start in it)."""
    cache = tr.fold_state.sum_params
    if id(fn) not in cache:
        cache[id(fn)] = {}  # (GLSL has no recursion: a guard only)
        if fn is tr.model.entry:
            return cache[id(fn)]
        later, tr.fold_state.sum_later = tr.fold_state.sum_later, False
        try:
            with asked_in(tr, fn):
                cache[id(fn)] = _programs(tr, fn)
        finally:
            tr.fold_state.sum_later = later
    return cache[id(fn)]


def _programs(tr: FoldEngine, fn: Symbol) -> dict[int, Program]:
    facts = function_facts(tr)
    if not facts.ok or any(isinstance(n, A.Discard) for n in fn.node.body.walk()):
        return {}
    out: dict[int, Program] = {}
    for i, (p, (_, ptype, d)) in enumerate(zip(fn.node.proto.params, fn.params)):
        psym = tr.model.symbol_of(p)
        if d == "inout" and psym is not None and ptype.base == "float" and ptype.is_scalar:
            program = _program(tr, fn, facts, psym)
            if program is not None:
                out[i] = program
    for sym in _globals_written(tr, fn):
        program = _program(tr, fn, facts, sym)
        if program is not None:
            out[_key(tr, sym)] = program
    return out


def _globals_written(tr: FoldEngine, fn: Symbol) -> list:
    """The float scalar globals `fn` writes, itself or through the functions it calls."""
    found = tr.fold_state.sum_globals
    if found is None:
        seen: dict[int, Any] = {}
        for f in tr.model.reachable_functions():
            for n in f.node.body.walk():
                sym = tr.model.symbol_of(n) if isinstance(n, A.Identifier) else None
                if sym is not None and sym.kind == "global" and _variable(sym):
                    seen.setdefault(id(sym), sym)
        found = tr.fold_state.sum_globals = list(seen.values())
    out = found
    return [
        g
        for g in out
        if g.type is not None
        and g.type.base == "float"
        and g.type.is_scalar
        and _writes_global(tr, fn, g)
    ]


def _program(tr: FoldEngine, fn: Symbol, facts: Any, sym: Any) -> Program | None:
    ws = _writes(tr, facts, sym)
    if not ws:
        return None
    body = fn.node.body.stmts
    chains = _chains(tr, facts, sym, ws, param_root=True)
    writes = [x for x in chains[0]["items"] if not isinstance(x, A.For)] if chains else []
    if len(chains) != 1 or len(writes) != len({id(w.node) for w in ws}):
        return None
    loops = [x for x in chains[0]["items"] if isinstance(x, A.For)]
    returns = [n for n in fn.node.body.walk() if isinstance(n, A.Return)]
    armed_returns = [
        r
        for r in returns
        if r is not body[-1]
        and not any(facts.contains(lp.body, r) for lp in loops)
        and _in_arms(facts, r)
    ]
    if any(
        r is not body[-1]
        and not any(facts.contains(lp.body, r) for lp in loops)
        and all(r is not x for x in armed_returns)
        for r in returns
    ) or any(facts.region[id(x)] != () for x in loops):
        return None  # (a return outside the unrolled loops: the rest runs on some lanes)
    where = chains[0]["where"]
    armed = [x for x in writes if where[id(x)][0] is None and facts.region[id(x)] != ()]
    if not all(_in_arms(facts, x) for x in armed):
        return None  # (a write in a loop NIR keeps: a phi follows, not the chain)
    ops = chains[0]["ops"]
    leaves = any(isinstance(op, Loop) and op.breaks for op in ops) or bool(armed or armed_returns)
    return Program(ops, chains[0]["where"], leaves)


def _in_arms(facts: Any, node: Any, top: Any = None) -> bool:
    """`node` is in arms of ``if`` statements only (no loop, switch or ``?:`` around it, up
    to `top`): NIR keeps the value written there and the one around it apart, a phi at the
    join."""
    up = facts.parent.get(id(node))
    while up is not None and up is not top:
        if isinstance(up, (A.For, A.While, A.DoWhile, A.Switch, A.Ternary, A.Binary)):
            return False
        up = facts.parent.get(id(up))
    return True


def chain_globals(tr: FoldEngine, fn: Symbol) -> list[tuple[int, Any]]:
    """(key, global) for each global among `fn`'s :func:`chain_params`: a call passes its value
    before the call as the base where a chain starts there."""
    return [(k, _global_of(tr, k)) for k in sorted(chain_params(tr, fn)) if k >= _GLOBALS]


def param_step(tr: FoldEngine, node: Any) -> tuple[int, int, int, Any, int] | None:
    """(the parameter's index, the slot of the node's first constant, the stride between two
    copies of its loop, the loop, how many constants it adds a copy) for a write of a
    :func:`chain_params` parameter of the function being emitted; else None."""
    fn = current_function(tr).sym
    if fn is None or isinstance(tr.fn, FunctionStandin):
        return None
    for i, program in chain_params(tr, fn).items():
        if id(node) in program.where:
            return (i, *program.slot(node))
    return None


def unrolled_chain(tr: FoldEngine, loop: Any, sym: Any) -> bool:
    """`loop` is one NIR unrolls (loop_unroll.nir_unrolls, with no loop, continue or
    discard in its body) and its body writes `sym` only by steps in its
    straight line: each copy continues the chain of the one before; or only in the branch
    :func:`folded_branch` finds (the second copy continues the first's, a phi follows)."""
    cache = tr.fold_state.sum_loops
    key = (id(loop), id(sym))
    if key not in cache:
        cache[key] = False
        facts = function_facts(tr)
        if nir_unrolls(tr, loop) and not any(
            isinstance(n, (A.Continue, A.Discard, A.For, A.While, A.DoWhile))
            for n in loop.body.walk()
        ):
            inner = facts.region[id(loop.body)]
            writes = [w for w in _writes(tr, facts, sym) if facts.contains(loop.body, w.node)]
            cache[key] = bool(writes) and all(
                facts.region[id(w.node)] == inner and _chain_write(tr, w.node, sym) for w in writes
            )
            if writes and not cache[key]:
                cache[key] = folded_branch(tr, loop, sym) is not None
    return cache[key]


def _chained_loop(tr: FoldEngine, loop: Any, sym: Any) -> bool:
    return unrolled_chain(tr, loop, sym) or (
        not tr.fold_state.sum_later and first_copy_loop(tr, loop, sym)
    )


def first_copy_loop(tr: FoldEngine, loop: Any, sym: Any) -> bool:
    """`loop` is one NIR unrolls whose body writes `sym` by steps in arms of ``if`` statements
    (or after them): its first copy continues the chain it is entered with (the writes there
    are SSA additions of that value), a later copy starts from the phi the arms join into.
    The chain takes the first copy (a loop op of one copy, left early: a phi after it)."""
    cache = tr.fold_state.sum_loops
    key = (id(loop), id(sym), "first")
    if key not in cache:
        cache[key] = False
        facts = function_facts(tr)
        if (
            not unrolled_chain(tr, loop, sym)
            and nir_unrolls(tr, loop)
            and not any(
                isinstance(n, (A.Continue, A.Discard, A.For, A.While, A.DoWhile))
                for n in loop.body.walk()
            )
        ):
            writes = [w for w in _writes(tr, facts, sym) if facts.contains(loop.body, w.node)]
            cache[key] = bool(writes) and all(
                _is_step(tr, w.node, sym)
                and _in_arms(facts, w.node, loop.body)
                and not (
                    isinstance(w.node, A.Call)
                    and any(isinstance(op, Loop) for op in _callee_program(tr, w.node).ops)
                )
                for w in writes
            )
        if cache[key]:
            fn = current_function(tr).sym
            tr.fold_state.sum_first.setdefault(id(fn), {})[id(loop)] = loop
    return cache[key]


def _chain_write(tr: FoldEngine, node: Any, sym: Any) -> bool:
    """A step of `sym`, or a call advancing it whose callee unrolls no loop of its own and
    leaves no phi after it (Program.leaves: writes in arms, an arm ending in a return)."""
    return _is_step(tr, node, sym) and not (
        isinstance(node, A.Call)
        and (
            any(isinstance(op, Loop) for op in _callee_program(tr, node).ops)
            or _callee_program(tr, node).leaves
        )
    )


_COMPARED = {"<": np.less, "<=": np.less_equal, ">": np.greater, ">=": np.greater_equal}
_SWAPPED = {"<": ">", "<=": ">=", ">": "<", ">=": "<="}


def folded_branch(tr: FoldEngine, loop: Any, sym: Any) -> Any:
    """The ``if`` of a two-pass `loop` NIR unrolls whose then-branch's straight line holds
    every write of `sym` in the body (steps), when NIR folds that branch away in the first
    copy and keeps it in the second: its condition compares a component of a local with a
    constant, the local a constant before the loop that the body writes after the condition
    (``vec3 d = vec3(0, 0, 1); for (2 passes) { if (d.y < 0.5) d = scatter(d); ... }``).
    The first copy's writes are then straight line, the second's dominated by them (the
    chain runs on), and a phi joins the second copy's branch (a third copy would restart
    there: not followed); else None."""
    cache = tr.fold_state.sum_loops
    key = ("branch", id(loop), id(sym))
    if key not in cache:
        cache[key] = None
        facts = function_facts(tr)
        if (
            isinstance(loop, A.For)
            and nir_unrolls(tr, loop)
            and trip_count(tr, loop) == 2
            and not any(
                isinstance(n, (A.Break, A.Return, A.Continue, A.Discard, A.For, A.While, A.DoWhile))
                for n in loop.body.walk()
            )
        ):
            inner = facts.region[id(loop.body)]
            writes = [w for w in _writes(tr, facts, sym) if facts.contains(loop.body, w.node)]
            branch = next(
                (
                    n
                    for n in loop.body.walk()
                    if isinstance(n, A.If)
                    and facts.region[id(n)] == inner
                    and writes
                    and all(facts.contains(n.then, w.node) for w in writes)
                ),
                None,
            )
            if (
                branch is not None
                and all(
                    facts.region[id(w.node)] == facts.region[id(branch.then)]
                    and _chain_write(tr, w.node, sym)
                    for w in writes
                )
                and _true_in_first_copy(tr, facts, loop, branch)
            ):
                cache[key] = branch
    return cache[key]


def _true_in_first_copy(tr: FoldEngine, facts: Any, loop: Any, branch: A.If) -> bool:
    """`branch`'s condition, ``x < #k`` (any order or comparison) with x a local or one of its
    components, is true on the value x holds before `loop`, a constant, and the body gives x
    another value after the ``if`` (so the second copy's condition is no constant)."""
    c = branch.cond
    if not isinstance(c, A.Binary) or c.op not in _COMPARED:
        return False
    if is_constant(tr, c.right) and not is_constant(tr, c.left):
        read, k, op = c.left, c.right, c.op
    elif is_constant(tr, c.left) and not is_constant(tr, c.right):
        read, k, op = c.right, c.left, _SWAPPED[c.op]
    else:
        return False
    comp = 0
    if isinstance(read, A.Field) and len(read.name) == 1:
        index = [s.find(read.name) for s in ("xyzw", "rgba", "stpq") if read.name in s]
        read, comp = read.base, index[0] if index else -1
    var = tr.model.symbol_of(read) if isinstance(read, A.Identifier) else None
    if var is None or var.kind != "local" or comp < 0:
        return False
    inside = [w for w in facts.writes_to(var) if facts.contains(loop.body, w.node)]
    if not inside or any(w.pos < facts.exit[id(c)] for w in inside):
        return False
    if not any(w.kind != "=" or w.value is None or not is_constant(tr, w.value) for w in inside):
        return False  # (a constant again: the second copy's branch is folded too)
    before = [w for w in facts.writes_to(var) if w.pos < facts.enter[id(loop)]]
    if not before:
        return False
    w = before[-1]
    if (
        w.kind not in ("=", "init")
        or w.value is None
        or not facts.dominates(w.node, loop)
        or facts.written_between(w.node, loop, [var])
    ):
        return False
    values, bound = constant_value(tr, w.value), constant_value(tr, k)
    if values is None or bound is None or len(bound) != 1 or comp >= len(values):
        return False
    return bool(_COMPARED[op](np.float32(values[comp]), np.float32(bound[0])))


def _phi_after(tr: FoldEngine, loop: Any, sym: Any) -> bool:
    """The value of `sym` after the unrolled `loop` is a phi: the loop can be left early, or
    the second copy's writes are in a branch (:func:`folded_branch`)."""
    return _leaves(loop) or folded_branch(tr, loop, sym) is not None


def _facts_of(tr: FoldEngine, fn: Symbol) -> Any:
    cache = tr.fold_state.fn_facts
    if id(fn) not in cache:
        cache[id(fn)] = FunctionFacts(fn.node, tr.model)
    return cache[id(fn)]


def _varying_start(tr: FoldEngine, e: Any, sym: Any) -> bool:
    """The value before the chain is no constant to NIR (``b(is_not_const)``: a constant is
    folded step by step instead)."""
    facts = function_facts(tr)
    before = [w for w in _writes(tr, facts, sym) if w.pos < facts.enter[id(e)]]
    if not before:  # (a global is its constant initializer at the start of the entry point)
        return sym.kind == "param" or sym.kind == "global" and not current_function(tr).is_entry
    w = before[-1]
    if w.kind in ("=", "init") and w.value is not None and facts.dominates(w.node, e):
        return is_varying(tr, w.value)
    return True


# -- the plan ----------------------------------------------------------------------------------
def chain_plan(tr: FoldEngine) -> dict[int, Entry]:
    """id(step, call or loop) -> its :class:`Entry`, for the chains of the function being
    emitted (its :func:`chain_params` variables apart: their steps read the caller's K)."""
    fn = current_function(tr).sym
    cache = tr.fold_state.sum_plans
    if id(fn) not in cache:
        cache[id(fn)] = {}
        facts = function_facts(tr)
        if facts.ok:
            own = chain_params(tr, fn)
            skip = {id(tr.model.symbol_of(fn.node.proto.params[i])) for i in own if i < _GLOBALS}
            skip |= {id(_global_of(tr, k)) for k in own if k >= _GLOBALS}
            if tr.fold_state.sum_later:
                skip = set()  # (a later pass of a first-copy loop: no caller's chain there)
            syms = {id(ws[0].symbol): ws[0].symbol for ws in facts.writes.values()}
            for g in _globals_written(tr, fn):
                syms.setdefault(id(g), g)
            for sym in syms.values():
                t = sym.type
                if (
                    id(sym) in skip
                    or not _variable(sym)
                    or t is None
                    or t.base != "float"
                    or t.is_matrix
                    or t.is_array
                ):
                    continue
                _plan_variable(tr, facts, sym, _writes(tr, facts, sym), cache[id(fn)])
    return cache[id(fn)]


def _plan_variable(tr: FoldEngine, facts: Any, sym: Any, ws: list, plan: dict) -> None:
    components = sym.type.size if sym.type.is_vector else 1
    for number, chain in enumerate(_chains(tr, facts, sym, ws, param_root=False), 1):
        ops = chain["ops"]
        if len(ops) == 1 and isinstance(ops[0], Step) or _size(ops) > _MOST:
            continue  # (one addition: as written; a very long chain too)
        per_component = []
        for c in range(components):
            got = chain_constants(_component(ops, c))
            if got is None:
                break
            per_component.append(got)
        else:
            for x in chain["items"]:
                loop, first, count = chain["where"][id(x)]
                ks = _ks(per_component, chain["where"], x, loop, first, count)
                plan[id(x)] = Entry(number, id(x) in chain["roots"], ks, loop, sym)


def _chains(tr: FoldEngine, facts: Any, sym: Any, ws: list, param_root: bool) -> list[dict]:
    """The chains of `sym` in the function being emitted, each {"ops": sum_order ops, "where":
    id(item) -> (its unrolled loop or None, first op, count), "items": its steps, calls and
    loops, "roots": ids of its first items}. A chain starts where a step has no previous one
    and the value is no constant, or (`param_root`: a chain parameter's program) at the
    parameter."""
    nodes: list = []
    for w in ws:
        if _is_step(tr, w.node, sym) and all(n is not w.node for n in nodes):
            nodes.append(w.node)
    if len(nodes) > _MOST:
        return []  # (left as written: the simulation grows with the square of a chain)
    loops: list = []
    for n in nodes:
        for lp in facts.enclosing_loops(n):
            if _chained_loop(tr, lp, sym) and all(lp is not x for x in loops):
                loops.append(lp)
    items = sorted(nodes + loops, key=lambda x: facts.enter[id(x)])
    chain_of: dict[int, int] = {}
    chains: list[dict] = []
    where: dict[int, tuple[Any, int, int]] = {}
    loop_ops: dict[int, list] = {}
    for x in items:
        loop = next((lp for lp in loops if lp is not x and facts.contains(lp.body, x)), None)
        prev = _previous_step(tr, x, sym)
        if loop is not None:  # (in an unrolled loop's body: its chain is the loop's)
            if id(loop) not in chain_of:
                continue
            ops, start = loop_ops[id(loop)], -1
            if prev is not loop:
                if prev is None or id(prev) not in where:
                    continue
                start = where[id(prev)][1] + where[id(prev)][2] - 1
            chain_of[id(x)] = chain_of[id(loop)]
        elif param_root and chains and (isinstance(prev, A.Param) or _first_write(tr, x, sym)):
            chain_of[id(x)] = 0  # (another arm of an if: the parameter's chain again)
            chains[0]["roots"].add(id(x))
            ops, start = chains[0]["ops"], -1
        elif prev is None or param_root and isinstance(prev, A.Param):
            if not param_root and not _varying_start(tr, x, sym):
                continue
            chain_of[id(x)] = len(chains)
            chains.append({"ops": [], "where": where, "items": [], "roots": {id(x)}})
            ops, start = chains[-1]["ops"], -1
        else:
            ref = _owner(loops, prev) or prev  # (after a loop: its last copy's value)
            if id(ref) not in chain_of or where[id(ref)][0] is not None:
                continue
            chain_of[id(x)] = chain_of[id(ref)]
            ops = chains[chain_of[id(x)]]["ops"]
            start = where[id(ref)][1] + where[id(ref)][2] - 1
        chains[chain_of[id(x)]]["items"].append(x)
        first = len(ops)
        if isinstance(x, A.For):
            body: list = []
            loop_ops[id(x)] = body
            copies = 1 if first_copy_loop(tr, x, sym) else loop_count(tr, x)
            ops.append(Loop(start, copies, body, _phi_after(tr, x, sym) or copies == 1))
        elif isinstance(x, A.Call):
            program = _callee_program(tr, x)
            for op in program.ops:  # (the callee's ops, its entry the value here)
                prev_op = start if op.prev < 0 else first + op.prev
                if isinstance(op, Loop):
                    ops.append(Loop(prev_op, op.count, op.body, op.breaks))
                else:
                    ops.append(Step(prev_op, op.k, op.neg))
        else:
            step = chain_step(tr, x)
            assert step is not None  # (an item of a chain: a call or a step)
            sign, k_node = step
            constants = constant_value(tr, k_node)
            assert constants is not None  # (chain_step's operand is a constant)
            values = [float(v) for v in constants]
            if sign == "-":
                values = [-v for v in values]
            ops.append(Step(start, values, sign == "-"))
        where[id(x)] = (loop, first, len(ops) - first)
    return chains


_MOST = 200  # additions a chain may have (copies of unrolled loops counted) to be followed


def _size(ops: list) -> int:
    return sum(1 if isinstance(op, Step) else op.count * _size(op.body) for op in ops)


def _owner(loops: list, prev: Any) -> Any:
    """The loop whose body `prev` is (the value after that loop), else None."""
    return next((lp for lp in loops if lp.body is prev), None)


def loop_count(tr: FoldEngine, loop: Any) -> int:
    """How many copies NIR makes of an unrolled loop (loop_unroll.trip_count), one for a
    :func:`first_copy_loop` (the copies its chain takes)."""
    if any(id(loop) in loops for loops in tr.fold_state.sum_first.values()):
        return 1
    count = trip_count(tr, loop)
    assert count is not None  # (an unrolled loop)
    return count


def _component(ops: list, c: int) -> list:
    out: list = []
    for op in ops:
        if isinstance(op, Loop):
            out.append(Loop(op.prev, op.count, _component(op.body, c), op.breaks))
        else:
            k = np.atleast_1d(op.k)
            out.append(Step(op.prev, k[c] if len(k) > 1 else k[0], op.neg))
    return out


def _ks(per_component: list, where: dict, x: Any, loop: Any, first: int, count: int) -> list:
    """The K of item `x` per copy of its loop: per component for a step, per slot of the
    callee's :class:`Program` for a call (its loops' copies one after the other)."""
    if isinstance(x, A.For):
        return []
    copies = 1 if loop is None else len(per_component[0][where[id(loop)][1]])
    out = []
    for j in range(copies):
        vals = []
        for got in per_component:
            level = got if loop is None else got[where[id(loop)][1]][j]
            vals.append(_flat(level[first : first + count]))
        out.append([v[0] for v in vals] if not isinstance(x, A.Call) else vals[0])
    return out


def _flat(values: list) -> list:
    out: list = []
    for v in values:
        if isinstance(v, list):
            for copy in v:
                out += _flat(copy)
        else:
            out.append(v)
    return out


def sum_entry(tr: FoldEngine, node: Any) -> Entry | None:
    """The :class:`Entry` of a step, call or loop of the function being emitted, else None."""
    if tr.fn is None or current_function(tr).sym is None:
        return None
    return chain_plan(tr).get(id(node))


def later_entry(tr: FoldEngine, node: Any) -> tuple[Any, Entry | None] | None:
    """For a step or call in a :func:`first_copy_loop` (whose :func:`sum_entry` or
    :func:`param_step` is its first pass's): (the loop, the :class:`Entry` of the passes after
    the first, None where they compute as written); else None. In those passes the variable
    is a phi at the top of the pass, and the chains start afresh from it (the plan made as if
    NIR kept the loop; its chain numbers are negative, apart from the first pass's)."""
    if tr.fn is None or current_function(tr).sym is None:
        return None
    fn = current_function(tr).sym
    facts = function_facts(tr)
    if not facts.ok or id(node) not in facts.enter:
        return None
    step = call_step(tr, node) if isinstance(node, A.Call) else chain_step(tr, node)
    if step is None:
        return None
    loops = tr.fold_state.sum_first.get(id(fn), {})
    loop = next((lp for lp in facts.enclosing_loops(node) if id(lp) in loops), None)
    if loop is None:
        return None
    cache = tr.fold_state.sum_later_plans
    if id(fn) not in cache:
        main = tr.fold_state.sum_plans.pop(id(fn), None)
        tr.fold_state.sum_later = True
        try:
            plan = chain_plan(tr)
        finally:
            tr.fold_state.sum_later = False
            if main is not None:
                tr.fold_state.sum_plans[id(fn)] = main
            else:
                tr.fold_state.sum_plans.pop(id(fn), None)
        for entry in plan.values():
            entry.chain = -entry.chain
        cache[id(fn)] = plan
    return loop, cache[id(fn)].get(id(node))


def indexed_loop(tr: FoldEngine, loop: Any) -> bool:
    """Some step in the unrolled `loop` has a K per copy, or a read merges a constant per copy
    (loop_copies.merging_loop): the engines count its passes."""
    fn = current_function(tr).sym if tr.fn is not None else None
    if fn is None:
        return False
    if merging_loop(tr, loop):
        return True  # (a constant merged into another value in the first copy: loop_copies.py)
    if id(loop) in tr.fold_state.sum_first.get(id(fn), {}):
        return True  # (the first pass continues a chain, the later ones start afresh)
    if any(p.where.get(id(loop)) for p in chain_params(tr, fn).values()):
        return True
    if ray_loop(tr, loop):
        return True  # (only the first copy passes a ray on: ray_dots.py)
    return any(e.loop is loop and len(e.ks) > 1 for e in chain_plan(tr).values())
