"""Globals no function writes, as constants of the generated module, and the per-pixel state
something writes.

A global whose initial value reads no uniform (`const` arrays of spheres and lights, a plain
global nothing assigns, a global initialized from such globals) and that no reachable function
writes holds the same value in every pixel of every frame. The module computes the initial
values once, when it is loaded, with its own compiled initializer (`globals_template`, the
function every frame calls: the same machine code, the same bits), into the arrays GCF, GCI,
GCU and GCB (module_text.FREEZE); the functions read those slots there instead of in the
per-pixel state (`gf`...). numba makes a global NumPy array a constant of the machine code it
compiles, so LLVM folds a load at a known index and what it feeds (a loop over the spheres
unrolled reads each sphere's values as constants, no select chain). init_globals itself still
writes the state arrays' slots: it reads an earlier global from there.

Not frozen: a global whose initializer reads a uniform (its value changes with the frame), and
nothing at all when a global initializer calls a user function (a call may run a loop, whose
budget and cap belong to a frame, not to the load).

A call whose value is the same in every pixel of every frame is computed there too
(`load_time_call`): `rotmat(-0.7)` in a raymarcher's distance function, which every pixel would
otherwise compute at every step (its sin and cos llvmpipe's, not cheap). The initializer calls
the same generated function with the same constant arguments, so the value has the call's bits.
A per-pixel module does the same once a frame with a call that also reads uniforms
(`rot(iTime * 0.3)`), read from the state's template, which no function writes.

The per-pixel reset (render_rows copying the template into the state before each pixel) is
needed only for the state kinds a function writes (`written_state`): the others hold the
template's values for the whole frame.
"""

from __future__ import annotations

import ast
from typing import Any

from ...frontend import syntax as A
from .values import KIND_ARRAY, Arr, leaves

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ...semantics.model import Model
    from ..cpu_core.facts import Facts

# the per-pixel state array of each scalar kind -> the module constant of its frozen slots
FROZEN_ARRAY = {"gf": "GCF", "gi": "GCI", "gu": "GCU", "gb": "GCB"}


def frozen_globals(model: Model, facts: Facts) -> set[int]:
    """The ids of the globals whose initial value is read from module constants: no function
    of the program (facts.functions: those the entry reaches) writes them, and their
    initializer reads no uniform (through the globals it reads, too)."""
    fixed: set[int] = set()  # globals whose initial value is the same in every frame
    for sym in model.globals:
        if (
            sym.kind != "global"
            or sym.type.contains_opaque
            or sym.qualifier in ("uniform", "in", "out")
        ):
            continue
        d = sym.node
        init = d.init if isinstance(d, A.Declarator) else None
        if init is None:
            fixed.add(id(sym))
            continue
        found = _frame_independent(model, init, fixed)
        if found is None:  # a user function call: the load runs no shader loop
            return set()
        if found:
            fixed.add(id(sym))
    return {k for k in fixed if k not in facts.written_globals}


def _frame_independent(model: Model, init: Any, fixed: set[int]) -> bool | None:
    """Whether an initializer reads neither a uniform nor a global whose initial value does;
    None when it calls a user function."""
    from ...semantics.model import Symbol

    ok = True
    for node in init.walk():
        if isinstance(node, A.Call) and isinstance(model.call_target(node), Symbol):
            return None
        if not isinstance(node, A.Identifier):
            continue
        sym = model.symbol_of(node)
        if sym is None:
            continue
        if sym.kind == "global":
            ok &= sym.qualifier != "uniform" and id(sym) in fixed
        elif sym.kind == "builtin-var":
            ok &= sym.const_value is not None  # gl_MaxDrawBuffers, not gl_FragCoord
        elif sym.kind == "uniform":
            ok = False
    return ok


def frozen_parts(parts: list) -> list:
    """A frozen global's parts as reads of the module constants (`gf[3]` -> `GCF[3]`)."""
    out: list = []
    for p in parts:
        if isinstance(p, Arr):
            out.append(Arr(FROZEN_ARRAY[p.name], p.off, p.size, p.base))
        else:
            name, rest = p.split("[", 1)
            out.append(f"{FROZEN_ARRAY[name]}[{rest}")
    return out


def written_state(functions: Any) -> dict[str, set | None]:
    """The per-pixel state each function (ast.FunctionDef) stores into, by array: the slots
    stored at constant indices, None when a store is at a run-time index or by aset (the
    whole array)."""
    written: dict[str, set | None] = {k: set() for k in FROZEN_ARRAY}

    def store(kind: str, index: Any) -> None:
        slots = written.get(kind)
        if slots is None:
            return
        if isinstance(index, ast.Constant) and isinstance(index.value, int):
            slots.add(index.value)
        else:
            written[kind] = None

    for f in functions:
        for n in ast.walk(f):
            if (
                isinstance(n, ast.Subscript)
                and isinstance(n.ctx, ast.Store)
                and isinstance(n.value, ast.Name)
            ):
                store(n.value.id, n.slice)
            elif (
                isinstance(n, ast.Call)
                and isinstance(n.func, ast.Name)
                and n.func.id == "aset"
                and n.args
                and isinstance(n.args[0], ast.Name)
            ):
                store(n.args[0].id, None)
    return written


def reset_kinds(written: dict[str, set | None]) -> set[str]:
    """The state arrays reset before each pixel: those some function writes."""
    return {k for k, slots in written.items() if slots is None or slots}


def load_time_call(
    model: Model, facts: Facts, frozen: set[int], call: A.Call, fn: Any
) -> str | None:
    """Whether the call of user function `fn` is the same in every pixel, and when it can be
    computed: "load" (once, when the module is loaded) or "frame" (once a frame: it reads a
    uniform), else None. Each argument is an expression of literals, frozen globals and
    uniforms (no user call), each parameter `in`, and `fn`, through the functions it calls,
    runs no loop (init_globals has no loop budget), reads no channel, no lane state and no
    global but the frozen ones, writes no global, never discards and takes no derivative."""
    from ...semantics.model import Symbol

    if fn.type.is_void or any(d != "in" for _, _, d in fn.params):
        return None
    frame = False
    for a in call.args:
        for n in a.walk():
            if isinstance(n, A.Call) and isinstance(model.call_target(n), Symbol):
                return None
            if isinstance(n, A.Identifier):
                sym = model.symbol_of(n)
                read = _frame_read(sym)
                if read is None and not (sym and sym.kind == "global" and id(sym) in frozen):
                    return None
                frame = frame or bool(read)
    if not facts.closed(fn) or id(fn) in facts.uses_derivs:
        return None
    if not facts.global_effects(fn)[0] <= frozen:
        return None
    seen: set[int] = set()
    todo = [fn]
    while todo:
        f = todo.pop()
        if id(f) in seen:
            continue
        seen.add(id(f))
        for n in f.node.body.walk():
            if isinstance(n, (A.For, A.While, A.DoWhile)):
                return None
            if isinstance(n, A.Identifier):
                sym = model.symbol_of(n)
                if sym is not None and sym.kind in ("uniform", "global", "builtin-var"):
                    read = _frame_read(sym)
                    if read is None and sym.kind != "global":
                        return None  # (a global read is one of the frozen ones: above)
                    frame = frame or bool(read)
            elif isinstance(n, A.Call):
                tgt = model.call_target(n)
                if isinstance(tgt, Symbol):
                    todo.append(tgt)
    return "frame" if frame else "load"


def _frame_read(sym: Any) -> bool | None:
    """True for a Shadertoy uniform that is no channel (the same in every pixel of a frame),
    False for a built-in constant, None for anything else."""
    if sym is None:
        return None
    if sym.kind == "uniform" or (sym.kind == "global" and sym.qualifier == "uniform"):
        return None if sym.type.contains_opaque else True
    if sym.kind == "builtin-var" and sym.const_value is not None:
        return False
    return None


def load_time_parts(cg: Any, call: A.Call, fn: Any) -> list | None:
    """The parts of a call that `load_time_call` allows and nothing of Mesa's across calls
    touches at this call site (no chain, sunk constant or ray passed in, no result kept in a
    register): slots of the per-pixel state that init_globals fills (`emit_load_time_calls`),
    read as module constants for a value of the load; the same call with the same arguments
    shares them. None for a call computed where it stands."""
    from ..cpu_core import nir_fold
    from ..cpu_core.nir_fold.ray_dots import ray_fn
    from .sum_chains import nir_chain_params

    when = load_time_call(cg.model, cg.facts, cg.frozen, call, fn)
    if when is None or (when == "frame" and not cg.frame_calls):
        return None
    ret = leaves(fn.type, call)
    if any(n is not None for _, n in ret):
        return None
    ctx = cg.fold_context()
    if (
        nir_chain_params(cg, fn)
        or any(True for _ in nir_fold.chain_globals(ctx, fn))
        or cg.sunk_chain(fn) is not None
        or ray_fn(ctx, fn) is not None
        or nir_fold.register_call(ctx, call, fn)
    ):
        return None
    # the variant the call would call: the NumPy backend's constant folding decides its text
    seed = frozenset(i for i, a in enumerate(call.args) if cg.lane_uniform(a))
    if seed and (id(fn), seed) not in cg.variants:
        cg.variants.add((id(fn), seed))
        cg.pending.append((fn, seed))
    key = (cg.variant_name(fn, seed), tuple(repr(A.dump(a)) for a in call.args))
    known = cg.load_calls.get(key)
    if known is None:
        parts = []
        for base, _ in ret:
            parts.append(f"{KIND_ARRAY[base]}[{cg.slots[base]}]")
            cg.slots[base] += 1
        known = cg.load_calls[key] = (call, fn, seed, parts)
    # a value of the frame is read from the state, which no function writes: the template
    # init_globals filled this frame (the lockstep rewrite reads it once for a block)
    return frozen_parts(known[3]) if when == "load" else list(known[3])


def emit_load_time_calls(cg: Any) -> None:
    """In init_globals: each call `load_time_parts` took, as the call site would have made it,
    into its slots."""
    for call, fn, seed, parts in cg.load_calls.values():
        cg.comment(call)
        args: list[str] = []
        for a in call.args:
            args += [p.whole() if isinstance(p, Arr) else p for p in cg.expr(a).parts]
        res = [cg.fresh() for _ in parts]
        name = cg.variant_name(fn, seed)
        cg.emit(f"{', '.join(res)}, = {name}({', '.join(cg.needs[cg.fn_name(fn)] + args)})")
        cg.write(parts, res)
