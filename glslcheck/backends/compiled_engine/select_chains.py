"""Runs of selects over conditions free of lanes, written once a lane (a lockstep rewrite):
a sprite's table, `idx = y == 14.0 ? (x <= 7.0 ? 40960.0 : 42.0) : idx;` one line a row, whose
W-lane selects and writes a row become one scalar pick of the last row that holds and one
write of W lanes.

`SelectChains` is a base class of lanes._Fn, whose state (`counts`, `reads`, `varying`, `ldiv`)
and emission (`is_varying`, `fresh`, `emit`, `stmt`) its methods use."""

from __future__ import annotations

import ast
import copy
import re
from dataclasses import dataclass
from typing import Any

from .lanes_slim import names_in
from .values import pure_expr

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up


_TEMP = re.compile(r"_t\d+")  # codegen's temporaries
_FLOAT_CONST = re.compile(r"F_\w+")  # codegen's float32 constants (`F_7p0`, `F_nan`)


class _Stale(Exception):
    """A temporary read after a write of a name its value reads (select_chain)."""


@dataclass
class _Chain:
    """A run of selects into one name (_Fn.select_chain): the name, the tree of selects over
    conditions with lanes its writes share (None: constants alone), each write's condition
    free of lanes and leaves, and the index of the statement after the run."""

    target: str
    tree: Any
    elems: list
    end: int


def _is_lsel(e: Any) -> bool:
    return (
        isinstance(e, ast.Call)
        and isinstance(e.func, ast.Name)
        and e.func.id == "lsel"
        and len(e.args) == 3
        and not e.keywords
    )


def _inline(e: Any, temps: dict, used: set, stale: set) -> Any:
    """e with the temporaries of temps read as their values (new nodes where anything changes;
    the nodes of e itself are not changed); None when it reads a stale one."""
    try:
        return _inlined(e, temps, used, stale)
    except _Stale:
        return None


def _inlined(e: Any, temps: dict, used: set, stale: set) -> Any:
    if isinstance(e, ast.Name):
        if isinstance(e.ctx, ast.Load):
            if e.id in stale:
                raise _Stale
            if e.id in temps:
                used.add(e.id)
                return temps[e.id]
        return e
    new = copy.copy(e)
    for field, value in ast.iter_fields(e):
        if isinstance(value, list):
            setattr(
                new,
                field,
                [_inlined(x, temps, used, stale) if isinstance(x, ast.AST) else x for x in value],
            )
        elif isinstance(value, ast.AST):
            setattr(new, field, _inlined(value, temps, used, stale))
    return new


def _const_leaf(e: Any, is_varying: Any) -> bool:
    """A float32 value free of lanes: a module constant, or a select of them over a condition
    free of lanes."""
    if isinstance(e, ast.Name):
        return _FLOAT_CONST.fullmatch(e.id) is not None
    return (
        _is_lsel(e)
        and not is_varying(e.args[0])
        and pure_expr(e.args[0])
        and _const_leaf(e.args[1], is_varying)
        and _const_leaf(e.args[2], is_varying)
    )


def is_temp_write(s: Any) -> bool:
    return (
        isinstance(s, ast.Assign)
        and len(s.targets) == 1
        and isinstance(s.targets[0], ast.Name)
        and _TEMP.fullmatch(s.targets[0].id) is not None
    )


def _fill(e: Any, values: Any, is_varying: Any) -> Any:
    """The tree e (_Fn.select_tree) with its leaves read from the names of values, in order."""
    if _const_leaf(e, is_varying):
        return ast.Name(next(values), ast.Load())
    return ast.Call(
        ast.Name("lsel", ast.Load()),
        [e.args[0], _fill(e.args[1], values, is_varying), _fill(e.args[2], values, is_varying)],
        [],
    )


class SelectChains:
    """The select-chain rewrite of one function (a mixin of lanes._Fn)."""

    if TYPE_CHECKING:
        counts: dict[str, int]
        reads: dict[str, int]
        varying: set[str]
        ldiv: Any

        def is_varying(self, e: Any) -> bool: ...
        def fresh(self, prefix: str) -> str: ...
        def emit(self, line: str) -> None: ...
        def stmt(self, s: Any, top: bool) -> None: ...

    def select_chain(self, stmts: list, i: int) -> _Chain | None:
        """The run of stmts from i that writes one name v as `v = lsel(a, e, v)` again and again
        (through codegen's temporaries, each written once and read once in the run), where each
        a is free of lanes and each e is one tree of selects over the same conditions with lanes
        and constants at its leaves: a sprite's table, `idx = y == 14.0 ? (x <= 7.0 ? 40960.0 :
        42.0) : idx;` one line a row. None when there is no such run of two writes or more."""
        temps: dict[str, Any] = {}  # the run's temporaries: their values, temporaries inlined
        used: set[str] = set()  # temporaries read by the writes so far
        stale: set[str] = set()  # temporaries that read v before a write of v
        target: str | None = None
        key: Any = "*"
        elems: list[tuple[Any, list, Any]] = []  # condition, leaves, tree (None: a leaf alone)
        end, count = i, 0
        for j in range(i, len(stmts)):
            s = stmts[j]
            if not (
                isinstance(s, ast.Assign)
                and len(s.targets) == 1
                and isinstance(s.targets[0], ast.Name)
            ):
                break
            name = s.targets[0].id
            value = _inline(s.value, temps, used, stale)
            if value is None:
                break
            if _TEMP.fullmatch(name) and self.counts.get(name) == 1 and self.reads.get(name) == 1:
                if not pure_expr(value):
                    break
                temps[name] = value
                continue
            if not (
                _is_lsel(value)
                and isinstance(value.args[2], ast.Name)
                and value.args[2].id == name
                and (target is None or name == target)
            ):
                break
            a, e = value.args[0], value.args[1]
            if name in names_in(a) or name in names_in(e) or self.is_varying(a) or not pure_expr(a):
                break
            found = self.select_tree(e)
            if found is None or (key != "*" and found[0] not in ("*", key)):
                break
            if key == "*":
                key = found[0]
            target = name
            elems.append((a, found[1], None if found[0] == "*" else e))
            stale |= {t for t, x in temps.items() if t not in used and name in names_in(x)}
            if set(temps) <= used:  # every temporary so far is read by the chain's writes
                end, count = j + 1, len(elems)
        if count < 2 or target is None:
            return None
        tree = next((t for _, _, t in elems[:count] if t is not None), None)
        # worth it where each write is W writes: a tree with lanes, v with lanes, or under a mask
        if tree is None and target not in self.varying and not self.ldiv:
            return None
        return _Chain(target, tree, [(a, leaves) for a, leaves, _ in elems[:count]], end)

    def select_tree(self, e: Any) -> tuple[Any, list] | None:
        """e as a tree of selects over conditions with lanes (the key: their text and the
        tree's form) and its leaves, each a float constant or a select of them over a condition
        free of lanes; "*" for a leaf alone (it fills every leaf of any tree)."""
        if _const_leaf(e, self.is_varying):
            return "*", [e]
        if _is_lsel(e):
            c = e.args[0]
            if not self.is_varying(c) or not pure_expr(c):
                return None
            left = self.select_tree(e.args[1])
            right = self.select_tree(e.args[2])
            if left is None or right is None:
                return None
            return (ast.dump(c), left[0], right[0]), left[1] + right[1]
        return None

    def fuse_chain(self, chain: _Chain, top: bool) -> int:
        """A select_chain run as one write: which of its conditions holds last and that write's
        leaves, chosen among constants free of lanes (one scalar each, not W), then `v =
        lsel(any condition, the tree over the chosen leaves, v)`: the same value the run leaves
        in every lane, one write of W lanes instead of a W-lane tree and a W-lane write a
        step. Returns the index of the statement after the run."""
        m = len(chain.elems[0][1]) if chain.tree is None else max(len(x) for _, x in chain.elems)
        hit = ""
        values: list[str] = []
        for a, leaves in chain.elems:
            leaves = leaves if len(leaves) == m else leaves * m  # a leaf alone fills the tree
            cond = self.scalar(ast.unparse(a))
            if not hit:
                hit = cond
                values = [self.scalar(ast.unparse(x)) for x in leaves]
                continue
            hit = self.scalar(f"{hit} | {cond}")
            values = [
                self.scalar(f"lsel({cond}, {ast.unparse(x)}, {p})") for x, p in zip(leaves, values)
            ]
        tree = ast.Name(values[0], ast.Load())
        if chain.tree is not None:
            tree = _fill(chain.tree, iter(values), self.is_varying)
        write = ast.Assign(
            [ast.Name(chain.target, ast.Store())],
            ast.Call(
                ast.Name("lsel", ast.Load()),
                [ast.Name(hit, ast.Load()), tree, ast.Name(chain.target, ast.Load())],
                [],
            ),
        )
        self.stmt(ast.fix_missing_locations(write), top)
        return chain.end

    def scalar(self, text: str) -> str:
        """text as a fresh name of one value for the block."""
        name = self.fresh("u")
        self.varying.discard(name)
        self.emit(f"{name} = {text}")
        return name
