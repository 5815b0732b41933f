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

The per-pixel reset (render_rows copying the template into the state before each pixel) is
needed only for the state kinds a function writes (`written_state`): the others hold the
template's values for the whole frame.
"""

from __future__ import annotations

import ast
from typing import Any

from ...frontend import syntax as A
from .values import Arr

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
