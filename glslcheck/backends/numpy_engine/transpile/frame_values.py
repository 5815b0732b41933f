"""Values computed once a frame: runs of statements whose every value is the same in every lane
of every tile, run by the first tile that reaches them and handed to the others.

A frame is cut into tiles (tiles.py), and each tile runs the whole shader. A value the
uniformity analysis keeps as one lane (backends/cpu_core/uniformity.py) is still computed once
per tile: `sSphere spheres[4]; initSphere(spheres[0], ...); ...` or a lights array built by
calls costs dozens of Python calls in every tile. Such a value depends on nothing but literals,
Shadertoy uniforms, never-written globals and other such values, so it is the same float32
result, bit for bit, in every tile of the frame. A run of statements qualifies (`qualifies`)
when each of them

- declares or writes only this function's own locals the analysis keeps uniform, each write
  free (no mask: no lane left out reads the variable again), at a uniform index;
- computes only uniform values, through calls of functions that read no lane state, write no
  global and never discard (`Facts.closed`);
- lies outside every loop and switch of its function (a loop's iterations differ), in a
  function that uses no derivatives.

Its code is then emitted as

    _fv7 = X.frame(S, 7)
    if _fv7 is None:
        <the statements>
        X.keep(S, 7, (v_spheres, ...))
    else:
        v_spheres, ... = _fv7

`X.frame` answers from the frame's table (`FrameSpec.values`, tiles.py: one per frame in this
process, one per frame in each worker process), or None where no table is kept (lane
statistics, llvmpipe's loop limiter: both count per tile what the statements' calls do). The
generated text is checked too (`_plain`): a run whose code names a mask, a lane field of `S` or
a lane helper is left as it is.
"""

from __future__ import annotations

import ast
import re
import textwrap
from collections.abc import Callable
from typing import Any

from ....frontend import syntax as A
from ....semantics.analysis import param_directions
from ....semantics.model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .state import TranspilerState

# Names the statements' code may read without having bound them: the runtime, module constants
# and zero values, user functions, and S itself (only as a function's first argument or for its
# uniform and global fields).
_CONSTANT_NAME = re.compile(r"(rt|S|C_\w+|Z_\w+)$")


def qualifies(t: TranspilerState, s: Any) -> bool:
    """True when statement `s`, at this point of the function being generated, computes values
    the same in every tile of the frame (the module docstring's conditions on the GLSL)."""
    fs = t.fn
    if fs is None or fs.uni is None or fs.loops or fs.switch_depth:
        return False
    if t.undefined != "zero" or t.watched is not None or id(fs.sym) in t.facts.uses_derivs:
        return False
    uni = fs.uni
    if isinstance(s, A.DeclarationStatement):
        d = s.decl
        if not isinstance(d, A.VariableDeclaration):
            return False
        for dec in d.declarators:
            sym = t.model.symbol_of(dec)
            if not _own_uniform(t, sym):
                return False
            if dec.init is not None and not uni.is_uniform(dec.init):
                return False
        return bool(d.declarators)
    if not isinstance(s, A.ExpressionStatement) or s.expr is None:
        return False
    e = s.expr
    if isinstance(e, A.Assignment):
        return (
            _free_target(t, e.target)
            and uni.is_uniform(e.value)
            and (e.op == "=" or uni.is_uniform(e.target))
        )
    if isinstance(e, A.Call) and not e.constructor:
        tgt = t.model.call_target(e)
        if not isinstance(tgt, Symbol) or not uni.is_uniform(e):
            return False
        dirs = param_directions(tgt)
        return all(
            _free_target(t, a) for d, a in zip(dirs, e.args, strict=False) if d in ("out", "inout")
        )
    return False


def worth_it(stmts: list[Any]) -> bool:
    """A run costs a table look-up a tile: worth it when it calls a function (not a
    constructor) or writes part of a variable (an element, a member)."""
    for s in stmts:
        for n in s.walk():
            if isinstance(n, A.Call) and not n.constructor:
                return True
            if isinstance(n, A.Assignment) and not isinstance(n.target, A.Identifier):
                return True
    return False


def wrap(t: TranspilerState, start: int, indent: int) -> None:
    """Make the lines emitted since `start` (at `indent`) a frame value, when their code is
    plain (`_plain`); otherwise leave them as they are."""
    lines = t.lines[start:]
    fs = t.fn
    assert fs is not None  # generating a function's body
    names = _plain(lines, lambda name: _own_uniform(t, fs.local_syms.get(name)))
    if not names:
        return
    fv = t.fresh("fv")
    key = t.n
    pad = "    " * indent
    bound = ", ".join(names) + ","
    t.lines[start:] = [
        f"{pad}{fv} = X.frame(S, {key})",
        f"{pad}if {fv} is None:",
        *("    " + line for line in lines),
        f"{pad}    X.keep(S, {key}, ({bound}))",
        f"{pad}else:",
        f"{pad}    {bound} = {fv}",
    ]


def _own_uniform(t: TranspilerState, sym: Symbol | None) -> bool:
    fs = t.fn
    assert fs is not None and fs.uni is not None  # (qualifies checked both)
    return (
        sym is not None
        and sym.kind in ("local", "param")
        and fs.uni.is_own(sym)
        and not fs.uni.is_varying(sym)
    )


def _free_target(t: TranspilerState, target: Any) -> bool:
    """An l-value of an own uniform variable, written without a mask at a uniform index."""
    fs = t.fn
    assert fs is not None and fs.uni is not None  # (qualifies checked both)
    root = target
    while isinstance(root, (A.Field, A.Index)):
        if isinstance(root, A.Index) and not fs.uni.is_uniform(root.index):
            return False
        root = root.base
    if not isinstance(root, A.Identifier):
        return False
    return _own_uniform(t, t.model.symbol_of(root)) and fs.uni.is_free(target)


def _plain(lines: list[str], uniform_local: Callable[[str], bool]) -> list[str]:
    """The names the code binds, in order, when it is a sequence of simple statements that reads
    only what it bound itself, the function's uniform locals (`uniform_local`), the runtime,
    constants, user functions and S's uniforms and globals; else []."""
    try:
        tree = ast.parse(textwrap.dedent("\n".join(lines)))
    except SyntaxError:
        return []
    bound: list[str] = []
    for node in tree.body:
        if not isinstance(node, (ast.Assign, ast.Expr)):
            return []
        value = node.value
        for n in ast.walk(value):
            if isinstance(n, ast.Name) and not _readable(n.id, bound, uniform_local):
                return []
            if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name):
                if n.value.id == "S" and not n.attr.startswith(("u_", "g_")):
                    return []
            if isinstance(n, (ast.Lambda, ast.NamedExpr, ast.Await, ast.Yield)):
                return []
        if isinstance(node, ast.Assign):
            for target in node.targets:
                for n in ast.walk(target):
                    if isinstance(n, ast.Name):
                        if not (n.id.startswith("_t") or uniform_local(n.id)):
                            return []
                        if n.id not in bound:
                            bound.append(n.id)
                    elif not isinstance(n, (ast.Tuple, ast.Store)):
                        return []
    if any(isinstance(n, ast.Name) and n.id == "S" and _bare_s(tree) for n in ast.walk(tree)):
        return []
    return bound


def _readable(name: str, bound: list[str], uniform_local: Callable[[str], bool]) -> bool:
    return (
        name in bound
        or uniform_local(name)
        or name.startswith("f_")
        or _CONSTANT_NAME.match(name) is not None
        or name == "None"
    )


def _bare_s(tree: ast.Module) -> bool:
    """True when S is used other than as a call's first argument or for `S.u_` / `S.g_`."""
    allowed: set[int] = set()
    for n in ast.walk(tree):
        if isinstance(n, ast.Call) and n.args and isinstance(n.args[0], ast.Name):
            if isinstance(n.func, ast.Name) and n.func.id.startswith("f_"):
                allowed.add(id(n.args[0]))
        if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name):
            allowed.add(id(n.value))
    return any(
        isinstance(n, ast.Name) and n.id == "S" and id(n) not in allowed for n in ast.walk(tree)
    )
