"""Warnings for undefined behaviour the two backends cannot agree on (a checked program only).

Both are legal GLSL ES 3.00 that the spec leaves undefined, so the NumPy backend and a GPU may
give different pixels; `check` warns (never errors) and `verify` may then report a mismatch:

* `index_warnings`: an index into an array, vector or matrix that is not a constant and cannot
  be shown to stay in range (spec 5.9 / 5.5: "behavior is undefined" for an index out of
  bounds). An index is in range when a small interval analysis bounds it: constants; the
  variable of a counting `for` loop (`for (int i = A; i < B; i++)`, `<=`, `i += c`, and the
  counting-down forms; its stride is taken into account) that the body does not assign;
  `+ - * /` of bounded values; `x % c` (x >= 0), `x & c`, `clamp(x, lo, hi)`, `min`, `max`,
  `abs`, `?:`, and int() of a bounded value. A bound may be one-sided (`min(x, 3)` <= 3).
  Anything else (a value computed from a float, a parameter, a variable assigned in the body)
  is unbounded and warned about.
* `output_warnings`: mainImage's `out vec4` colour not written on some path to a `return` or
  the end of the body (spec 6.1.1: an `out` parameter left unwritten is undefined when copied
  out). A path counts as writing the colour when every component the pass shows is assigned:
  red, green and blue in the Image tab (its alpha is set to 1 by Shadertoy), all four in a
  Buffer tab. A branch writes only when both arms do; a loop body may not run; a switch is
  taken as writing nothing unless the colour was written before it; an `out`/`inout`
  argument counts as a write of the whole colour; `discard` ends the path without a warning.
* `undefined_read_warnings`: each read of a value GLSL leaves undefined that the analysis finds
  (`analysis.undefined_reads`: an out parameter or a local read before it is written, integer
  division by zero, out-of-range shifts and conversions, built-ins outside their domain on
  constants), at the read.
"""

from __future__ import annotations

import math

from ..base.diagnostics import Diagnostic
from ..frontend import syntax as A
from ..language import glsl_types as T
from .analysis.undefined import undefined_reads
from .model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from .model import Model

RULE = "undefined-behaviour"


def hazard_warnings(model: Model) -> list[Diagnostic]:
    """Every kind of warning for a model without errors (the caller sorts them)."""
    out: list[Diagnostic] = []
    for fn in model.reachable_functions():
        definition = fn.node
        if isinstance(definition, A.FunctionDefinition) and definition.body is not None:
            out += index_warnings(model, definition)
    entry = model.entry
    if (
        entry is not None
        and entry.name == "mainImage"
        and isinstance(entry.node, A.FunctionDefinition)
    ):
        out += output_warnings(model, entry.node)
    return out + undefined_read_warnings(model)


def undefined_read_warnings(model: Any) -> list[Diagnostic]:
    return [
        Diagnostic(u.message, u.loc, severity="warning", rule=RULE, help=u.help)
        for u in undefined_reads(model)
    ]


# ---------------------------------------------------------------------------------------------
# Indexes


def index_warnings(model: Model, definition: A.FunctionDefinition) -> list[Diagnostic]:
    indexes, fors = [], []  # one walk of the body finds both
    for node in model.body_nodes(definition):
        t = type(node)
        if t is A.Index:
            indexes.append(node)
        elif t is A.For:
            fors.append(node)
    loops = loop_ranges(model, fors)
    out = []
    for node in indexes:
        if model.const_value(node.index) is not None:
            continue
        base_t = model.type_of(node.base)
        size = (
            base_t.array_size
            if isinstance(base_t, T.ArrayType)
            else (base_t.cols if base_t.is_matrix else base_t.size)
        )
        if not size:
            continue
        bounds = _interval(model, node.index, loops, 0)
        if 0 <= bounds[0] and bounds[1] <= size - 1:
            continue
        what = "array" if base_t.is_array else ("matrix" if base_t.is_matrix else "vector")
        known = f" (it can be {_show(bounds)})" if all(map(math.isfinite, bounds)) else ""
        out.append(
            Diagnostic(
                f"this index may be outside 0..{size - 1} of the {what}{known}; "
                "an index out of range is "
                "undefined behaviour, so the NumPy backend and the GPU may disagree",
                node.index.loc,
                severity="warning",
                rule=RULE,
                help=f"keep it in range, e.g. clamp(index, 0, {size - 1})",
            )
        )
    return out


def _show(bounds: tuple[float, float]) -> str:
    lo, hi = (int(b) if b == int(b) else b for b in bounds)
    return f"{lo}..{hi}"


def _writes(model: Model, body: A.Node, sym: Symbol) -> bool:
    """Whether `body` assigns `sym` (=, op=, ++, --)."""
    for n in body.walk():
        target = (
            n.target
            if type(n) is A.Assignment
            else n.operand
            if (type(n) is A.Unary or type(n) is A.Postfix) and n.op in ("++", "--")
            else None
        )
        if type(target) is A.Identifier and model.symbol_of(target) is sym:
            return True
    return False


def loop_ranges(model: Model, fors: list[A.For]) -> dict[int, tuple[float, float]]:
    """id(loop variable symbol) -> the values it takes in the body of its counting for loop
    (`fors`: the for statements of a function, in walk order)."""
    out: dict[int, tuple[float, float]] = {}
    for loop in fors:
        if type(loop.init) is not A.DeclarationStatement or loop.body is None:
            continue
        decl = loop.init.decl
        if type(decl) is not A.VariableDeclaration or len(decl.declarators) != 1:
            continue
        d = decl.declarators[0]
        sym = model.symbol_of(d)
        start = model.const_value(d.init) if d.init is not None else None
        if sym is None or not isinstance(start, int) or isinstance(start, bool):
            continue
        step = _step(model, loop.step, sym)
        limit = _limit(model, loop.cond, sym)
        if step is None or limit is None or _writes(model, loop.body, sym):
            continue
        op, bound = limit
        # The values are start, start + step, ...: the last one is the last of those in range.
        if step > 0 and op in ("<", "<="):
            hi = bound - 1 if op == "<" else bound
            if hi >= start:
                out[id(sym)] = (start, start + (hi - start) // step * step)
        elif step < 0 and op in (">", ">="):
            lo = bound + 1 if op == ">" else bound
            if lo <= start:
                out[id(sym)] = (start - (start - lo) // -step * -step, start)
    return out


def _is(model: Model, e: Any, sym: Symbol) -> bool:
    return type(e) is A.Identifier and model.symbol_of(e) is sym


def _step(model: Model, e: Any, sym: Symbol) -> int | None:
    """+c or -c for `i++`, `++i`, `i--`, `i += c`, `i -= c`, `i = i + c` (c a positive constant)."""
    if type(e) in (A.Unary, A.Postfix) and e.op in ("++", "--") and _is(model, e.operand, sym):
        return 1 if e.op == "++" else -1
    if type(e) is A.Assignment and _is(model, e.target, sym):
        if e.op in ("+=", "-="):
            c = model.const_value(e.value)
            if isinstance(c, int) and not isinstance(c, bool) and c > 0:
                return c if e.op == "+=" else -c
        if (
            e.op == "="
            and type(e.value) is A.Binary
            and e.value.op in ("+", "-")
            and _is(model, e.value.left, sym)
        ):
            c = model.const_value(e.value.right)
            if isinstance(c, int) and not isinstance(c, bool) and c > 0:
                return c if e.value.op == "+" else -c
    return None


_FLIP = {"<": ">", "<=": ">=", ">": "<", ">=": "<="}


def _limit(model: Model, cond: Any, sym: Symbol) -> tuple[str, int] | None:
    """(op, bound) for a condition `i op bound` or `bound op i` with a constant bound."""
    if type(cond) is not A.Binary or cond.op not in _FLIP:
        return None
    if _is(model, cond.left, sym):
        op, other = cond.op, cond.right
    elif _is(model, cond.right, sym):
        op, other = _FLIP[cond.op], cond.left
    else:
        return None
    bound = model.const_value(other)
    if not isinstance(bound, int) or isinstance(bound, bool):
        return None
    return op, bound


def _interval(model: Model, e: Any, loops: dict, depth: int) -> tuple[float, float]:
    """[lo, hi] of an int expression, each end possibly infinite (unknown)."""
    if depth > 32:
        return UNKNOWN
    value = model.const_value(e)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return (value, value)
    rec = lambda x: _interval(model, x, loops, depth + 1)  # noqa: E731
    t = type(e)
    if t is A.Identifier:
        sym = model.symbol_of(e)
        return loops.get(id(sym), UNKNOWN) if sym is not None else UNKNOWN
    if t is A.Binary:
        return _binary(e, rec)
    if t is A.Ternary:
        a, b = rec(e.then), rec(e.else_)
        return (min(a[0], b[0]), max(a[1], b[1]))
    if t is A.Unary and e.op in ("+", "-"):
        a = rec(e.operand)
        return a if e.op == "+" else (-a[1], -a[0])
    if t is A.Call:
        return _call(e, rec)
    return UNKNOWN


INF = float("inf")
UNKNOWN = (-INF, INF)


def _exact(x: tuple[float, float]) -> bool:
    return x[0] == x[1]


def _binary(e: A.Binary, rec) -> tuple[float, float]:
    a, b = rec(e.left), rec(e.right)
    if e.op == "%":  # GLSL ES 3.00 5.9: undefined for a negative operand; else 0..c-1 for c > 0
        if _exact(b) and b[0] > 0 and a[0] >= 0:
            return (0, min(a[1], b[0] - 1))
        return UNKNOWN
    if e.op == "&":
        for y in (a, b):
            if _exact(y) and y[0] >= 0:
                return (0, y[0])
        return UNKNOWN
    if e.op == "+":
        return (a[0] + b[0], a[1] + b[1])
    if e.op == "-":
        return (a[0] - b[1], a[1] - b[0])
    if e.op == "*" and all(map(math.isfinite, (*a, *b))):
        ps = [x * y for x in a for y in b]
        return (min(ps), max(ps))
    if e.op == "/" and b[0] > 0 and all(map(math.isfinite, (*a, *b))):  # by a positive value
        ps = [x / y for x in a for y in b]
        return (min(ps), max(ps))
    return UNKNOWN


def _call(e: A.Call, rec) -> tuple[float, float]:
    args = [rec(a) for a in e.args]
    name = e.callee
    if e.constructor and name in ("int", "uint") and len(args) == 1:
        # int(i) of an int keeps its interval; of a float: truncation keeps the bounds' floor/ceil
        return (
            math.floor(args[0][0]) if math.isfinite(args[0][0]) else -INF,
            math.ceil(args[0][1]) if math.isfinite(args[0][1]) else INF,
        )
    if name == "clamp" and len(args) == 3:
        (xlo, xhi), (lo, _), (_, hi) = args
        return (max(min(xlo, hi), lo), min(max(xhi, lo), hi))
    if name == "min" and len(args) == 2:
        return (min(args[0][0], args[1][0]), min(args[0][1], args[1][1]))
    if name == "max" and len(args) == 2:
        return (max(args[0][0], args[1][0]), max(args[0][1], args[1][1]))
    if name == "abs" and len(args) == 1:
        lo, hi = args[0]
        return (0 if lo <= 0 <= hi else min(abs(lo), abs(hi)), max(abs(lo), abs(hi)))
    return UNKNOWN


# ---------------------------------------------------------------------------------------------
# The colour output


def output_warnings(model: Model, definition: A.FunctionDefinition) -> list[Diagnostic]:
    params = definition.proto.params
    if not params or definition.body is None:
        return []
    sym = model.symbol_of(params[0])
    if (
        sym is None
        or params[0].name is None
        or "out" not in params[0].qualifiers
        and "inout" not in params[0].qualifiers
    ):
        return []
    need = 0b0111 if model.tab in ("Image", "GLSL") else 0b1111
    flow = _Flow(model, sym, need)
    end = flow.block(definition.body.stmts, 0)
    out = [
        Diagnostic(
            f"'{sym.name}' is not written on this path to the return; "
            "its colour is then undefined, so the "
            "NumPy backend and the GPU may disagree",
            loc,
            severity="warning",
            rule=RULE,
            help=f"give '{sym.name}' a value before every return (or at the top of mainImage)",
        )
        for loc in flow.unwritten_returns
    ]
    if end is not None and end & need != need:
        where = definition.proto.name_loc if definition.proto.name_loc.line else definition.loc
        out.append(
            Diagnostic(
                f"'{sym.name}' is not written on every path through mainImage; where it is not, "
                "the pixel's colour is undefined, so the NumPy backend and the GPU may disagree",
                where,
                severity="warning",
                rule=RULE,
                help=f"give '{sym.name}' a value on every path (or at the top of mainImage)",
            )
        )
    return out


class _Flow:
    """Which components of the colour are certainly written, statement by statement. A state
    is a 4-bit mask (x, y, z, w), or None after a statement no path falls out of."""

    def __init__(self, model: Model, sym: Symbol, need: int):
        self.model, self.sym, self.need = model, sym, need
        self.unwritten_returns: list = []

    def block(self, stmts: list, state: int | None) -> int | None:
        for s in stmts:
            if state is None:
                return None
            state = self.stmt(s, state)
        return state

    def stmt(self, s: Any, state: int) -> int | None:
        t = type(s)
        if t is A.Compound:
            return self.block(s.stmts, state)
        if t is A.If:
            state |= self.writes(s.cond)
            then = self.stmt(s.then, state) if s.then is not None else state
            other = self.stmt(s.else_, state) if s.else_ is not None else state
            if then is None or other is None:
                return other if then is None else then
            return then & other
        if t in (A.For, A.While):
            before = state | self.writes(s.init) if t is A.For and s.init is not None else state
            cond = s.cond if type(s.cond) is not A.ConditionDeclaration else s.cond.init
            before |= self.writes(cond)
            if s.body is not None:
                self.stmt(s.body, before)  # for the returns inside it
            return before  # the body may not run
        if t is A.DoWhile:
            after = self.stmt(s.body, state) if s.body is not None else state
            return None if after is None else after | self.writes(s.cond)
        if t is A.Switch:
            state |= self.writes(s.expr)
            current: int | None = state
            for part in s.body:  # each case label is entered with the state before the switch
                if type(part) is A.Case:
                    current = state
                elif current is not None:
                    current = self.stmt(part, current)
            return state
        if t is A.Return:
            state |= self.writes(s.value)
            if state & self.need != self.need:
                self.unwritten_returns.append(s.loc)
            return None
        if t is A.Discard:
            return None
        if t in (A.Break, A.Continue):
            return None
        return state | self.writes(s)

    def writes(self, node: Any) -> int:
        """The components a statement or expression certainly writes (anywhere inside it)."""
        if node is None:
            return 0
        mask = 0
        for n in _walk(node):
            if type(n) is A.Assignment:
                mask |= self.target_mask(n.target)
            elif type(n) is A.Call:
                target = self.model.call_target(n)
                if isinstance(target, Symbol) and target.params:
                    for arg, (_, _, direction) in zip(n.args, target.params):
                        if direction in ("out", "inout"):
                            mask |= self.target_mask(arg)
        return mask

    def target_mask(self, target: Any) -> int:
        if type(target) is A.Identifier:
            return 0b1111 if self.model.symbol_of(target) is self.sym else 0
        if (
            type(target) is A.Field
            and self.model.is_swizzle(target)
            and type(target.base) is A.Identifier
            and self.model.symbol_of(target.base) is self.sym
        ):
            return sum(1 << i for i in self.model.swizzle_indices(target))
        if (
            type(target) is A.Index
            and type(target.base) is A.Identifier
            and self.model.symbol_of(target.base) is self.sym
        ):
            i = self.model.const_value(target.index)
            return 1 << i if isinstance(i, int) and 0 <= i < 4 else 0
        return 0


def _walk(node: Any) -> Iterator[Any]:
    return node.walk() if isinstance(node, A.Node) else iter(())
