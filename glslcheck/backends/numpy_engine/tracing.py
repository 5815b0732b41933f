"""The tracing emission mode of the transpiler and the tracers its modules call (`glslcheck probe`).

`TraceTranspiler` is the code generator of transpile/ with hooks added: the module it writes
runs the same lane model and the same runtime calls, plus calls of `T`, a tracer that the caller
puts in the module's namespace before a run (`ns["T"] = tracer`):

    T.a(S, site, mask, value)                a variable was declared or assigned; value: the
                                             variable
    T.b(S, site, mask, cond) -> cond         the condition of an if or the selector of a switch
    T.r(S, site, mask, value) -> value       the value of a return statement
    T.e(S, site, mask)                       break, continue or discard
    T.le / T.li / T.lx(S, site, mask)        a loop starts, one of its iterations starts, it ends
    T.call(S, site, mask, f, call_mask, *args) -> f(S, call_mask, *args)   a user function call
    T.o(S, site, mask, fn, *args) -> fn(*args)   a float operator or built-in that can make NaN/Inf
    T.u(S, site, mask, value) -> value       an undefined value enters (semantics.analysis.
                                             undefined: an out parameter or a local that is read
                                             before it is written, at its declaration; an
                                             operation on constants outside its range); value:
                                             what this render gives it

`site` indexes `TraceTranspiler.sites` (file, line, column, source line, kind, name). The normal
module (`transpile.transpile`) has none of this and is not changed by it; the only difference in
behaviour is that the traced module never uses the early-out select (`Transpiler.early_out`),
which computes both returns of `if (c) return K; return e;`, so that a return is traced only
where it runs.

Tracers (any lane count, also under compaction: `LaneTracer.ids` maps a compacted state's lanes
back to the lanes of the run):

* `LaneTracer` finds, for every lane, where its first NaN or Inf appeared. An operation whose
  result is NaN/Inf in an active lane makes a candidate (the operation, classified: 0/0, sqrt of
  a negative, normalize of a zero vector, overflow, ...); the first write (assignment, return,
  argument) of a NaN/Inf value in a lane with no origin yet makes the lane's origin that
  candidate, or the write itself when no operation made it (a constant such as 1e39). A
  candidate from a side that a select threw away is dropped at the next finite write of its
  function (deeper calls do not drop their caller's candidates).
* `PixelTracer` does the same and also records every step one lane executed, with its value.
"""

from __future__ import annotations

import math
import operator
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...base.diagnostics import source_line
from ...frontend import syntax as A
from ...frontend.printer import to_glsl
from ...semantics.analysis import origins
from .runtime_values import Struct
from .transpile import Transpiler

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ...semantics.model import Model, Symbol

MAX_STEPS = (
    200_000  # steps PixelTracer records; later steps only count (a runaway shader stays bounded)
)

# built-ins that never turn finite arguments into NaN or Inf: not wrapped
_SAFE_BUILTINS = {
    "abs",
    "sign",
    "floor",
    "ceil",
    "trunc",
    "round",
    "roundEven",
    "min",
    "max",
    "clamp",
    "step",
    "radians",
    "degrees",
    "lessThan",
    "lessThanEqual",
    "greaterThan",
    "greaterThanEqual",
    "equal",
    "notEqual",
    "any",
    "all",
    "not",
    "transpose",
    "floatBitsToInt",
    "floatBitsToUint",
    "isnan",
    "isinf",
    "sin",
    "cos",
    "tanh",
    "atan",
}
_PY_OPERATORS = {"+": "add", "-": "sub", "*": "mul", "/": "truediv"}
_CALL_PREFIX = re.compile(r"^rt\.(\w+)\(")


@dataclass(frozen=True)
class Site:
    """A place in the user's GLSL that the traced module reports: what kind of step it is
    (assign, branch, loop, call, return, discard, or op for an operation), its location, the
    source line, a name (variable, function, `if`, operator) and the GLSL expression text."""

    kind: str
    path: str
    line: int
    column: int
    code: str
    name: str
    expr: str = ""
    function: str = ""
    params: tuple[str, ...] = ()  # a call's in and inout parameters, in order
    loop_step: bool = False  # the step of a for loop (run unmasked for an induction variable)
    why: str = ""  # an undefined value's site: the kind of read (semantics.analysis.undefined)
    read_line: int = 0  # ... and the line of its first undefined read


class TraceTranspiler(Transpiler):
    """`TraceTranspiler(model, path).module()` -> (source, meta) of the traced module; the
    sites its hooks name are `self.sites` afterwards."""

    CSE_CALLS = False  # every call where it runs, each reported (not one shared by repeats)

    def __init__(self, model: Model, path: str = "<shader>") -> None:
        super().__init__(model, path)
        self.sites: list[Site] = []
        self._site_ids: dict[tuple, int] = {}
        self.watched: dict[int, tuple[str, Any, str]] = {}  # id(expr) -> (hook, statement, name)
        self._stmt: Any = None  # the statement being emitted (for writes)
        self._ops: list[
            tuple[Any, str | None]
        ] = []  # (expression, mask) of the operators being printed
        self._loop_bodies: dict[int, int] = {}  # id(loop body) -> loop site
        self._glsl: dict[str, str] = {}  # Python name -> GLSL name
        self._loop_steps: set[int] = set()  # id() of for-loop steps
        # id(node) -> the undefined read it starts (T.u); an out parameter left unwritten on
        # some path is undefined only where the caller reads it after such a path: not traced
        self.undefined_at = {
            k: u for k, u in origins(model).items() if u.kind != "out-parameter-unwritten"
        }

    # -- sites -------------------------------------------------------------------------------------
    def site(
        self,
        kind: str,
        node: Any,
        name: str = "",
        expr: Any = None,
        params: tuple = (),
        why: Any = None,
    ) -> int:
        key = (kind, id(node), name)
        sid = self._site_ids.get(key)
        if sid is None:
            loc = node.loc
            code = (source_line(loc.path, loc.line) or "").strip()
            text = to_glsl(expr) if expr is not None else ""
            fname = self.fn.sym.name if self.fn is not None else ""
            self.sites.append(
                Site(
                    kind,
                    loc.path,
                    loc.line,
                    loc.column,
                    code,
                    name,
                    text,
                    fname,
                    params,
                    id(node) in self._loop_steps,
                    why.kind if why is not None else "",
                    why.loc.line if why is not None else 0,
                )
            )
            sid = self._site_ids[key] = len(self.sites) - 1
        return sid

    def _traced(self) -> bool:
        """Hooks go in function bodies only (not in module constants or global initializers)."""
        return self.fn is not None and not self.in_const and self.fn.sym.name != "<globals>"

    # -- what is traced ----------------------------------------------------------------------------
    def var_name(self, sym: Symbol, node: Any) -> str:
        name = super().var_name(sym, node)
        self._glsl.setdefault(name, sym.name)
        return name

    def early_out(self, body: list[Any]) -> None:
        return None  # the select computes the return that does not happen: not traceable

    def gen_function(self, sym: Symbol) -> None:
        for n in sym.node.body.walk():
            if isinstance(n, A.If):
                self.watched[id(n.cond)] = ("b", n, "if" if n.else_ is None else "if/else")
            elif isinstance(n, A.Switch):
                self.watched[id(n.expr)] = ("b", n, "switch")
            elif isinstance(n, A.Return) and n.value is not None:
                self.watched[id(n.value)] = ("r", n, sym.name)
        super().gen_function(sym)

    def comment_line(self, node: Any) -> None:
        self._stmt = node
        super().comment_line(node)

    def initial(self, t: Any, node: Any, mask: str | None = None) -> str:
        text = super().initial(t, node, mask)
        u = self.undefined_at.get(id(node))
        if u is None or not self._traced():
            return text
        sid = self.site("undefined", node, u.symbol.name if u.symbol else "", why=u)
        return f"T.u(S, {sid}, {mask}, {text})"

    def entry_prologue(self) -> list[str]:
        """A global the checker finds read before it is assigned enters undefined at the entry
        point's start: a step there (at its declaration's line)."""
        out = super().entry_prologue()
        for u in self.undefined_at.values():
            if u.kind == "uninitialized-global" and u.symbol is not None:
                sid = self.site("undefined", u.origin, u.symbol.name, why=u)
                name = self.var_name(u.symbol, u.origin)
                out.append(f"{name} = T.u(S, {sid}, _m, {name})")
        return out

    def expr(self, e: Any, mask: str | None) -> str:
        text = super().expr(e, mask)
        u = self.undefined_at.get(id(e))
        if u is not None and self._traced():
            sid = self.site("undefined", e, to_glsl(e), e, why=u)
            text = f"T.u(S, {sid}, {mask}, {text})"
        watch = self.watched.get(id(e))
        if watch is None or not self._traced():
            return text
        hook, stmt, name = watch
        sid = self.site("branch" if hook == "b" else "return", stmt, name)
        return f"T.{hook}(S, {sid}, {mask}, {text})"

    def _stmt_DeclarationStatement(self, s: A.DeclarationStatement, mask: str | None) -> None:
        super()._stmt_DeclarationStatement(s, mask)
        d = s.decl
        if not isinstance(d, A.VariableDeclaration):
            return
        for dec in d.declarators:
            sym = self.model.symbol_of(dec)
            if sym is not None and dec.init is not None:
                self.emit(
                    f"T.a(S, {self.site('assign', dec, sym.name)}, {mask}, "
                    f"{self.var_name(sym, dec)})"
                )

    def write(self, lv: Any, value: str, mask: str | None) -> None:
        super().write(lv, value, mask)
        if self._traced() and self._stmt is not None:
            name = self._glsl.get(lv.base, lv.base)
            self.emit(f"T.a(S, {self.site('assign', self._stmt, name)}, {mask}, {lv.base})")

    def _event(self, s: Any, kind: str, name: str, mask: str | None) -> None:
        self.emit(f"T.e(S, {self.site(kind, s, name)}, {mask})")

    def _stmt_Break(self, s: A.Break, mask: str | None) -> None:
        super()._stmt_Break(s, mask)
        assert self.fn is not None  # generating a function's body
        self._event(
            s, "branch", "break" if self.fn.loops[-1].kind == "loop" else "break (switch)", mask
        )

    def _stmt_Continue(self, s: A.Continue, mask: str | None) -> None:
        super()._stmt_Continue(s, mask)
        self._event(s, "branch", "continue", mask)

    def _stmt_Discard(self, s: A.Discard, mask: str | None) -> None:
        self._event(s, "discard", "discard", mask)
        super()._stmt_Discard(s, mask)

    def loop(
        self, s: Any, mask: str | None, cond: Any, body: Any, step: Any, do_while: bool
    ) -> None:
        name = {"For": "for", "While": "while", "DoWhile": "do"}.get(type(s).__name__, "loop")
        sid = self.site("loop", s, name)
        self._loop_bodies[id(body)] = sid
        if step is not None:
            self._loop_steps.add(id(step))
        self.emit(f"T.le(S, {sid}, {mask})")
        super().loop(s, mask, cond, body, step, do_while)
        self.emit(f"T.lx(S, {sid}, {mask})")

    def sub(self, s: Any, mask: str | None) -> None:
        sid = self._loop_bodies.get(id(s))
        if sid is not None:
            self.emit(f"T.li(S, {sid}, {mask})")
        super().sub(s, mask)

    def call_text(
        self, e: A.Call, fn: Symbol, call_mask: str | None, args: list[str], mask: str | None
    ) -> str:
        text = super().call_text(e, fn, call_mask, args, mask)
        if not self._traced():
            return text
        sid = self.site("call", e, fn.name, params=tuple(p for p, _, d in fn.params if d != "out"))
        return (
            f"T.call(S, {sid}, {mask}, {self.fn_name(fn)}, "
            f"{call_mask}{''.join(', ' + x for x in args)})"
        )

    # -- operations that can make NaN or Inf -------------------------------------------------------
    def _print_Binary(self, e: A.Binary, mask: str | None) -> str:
        self._ops.append((e, mask))
        try:
            return super()._print_Binary(e, mask)
        finally:
            self._ops.pop()

    def assignment(self, e: A.Assignment, mask: str | None, want_value: bool) -> str:
        self._ops.append((e, mask))
        try:
            return super().assignment(e, mask, want_value)
        finally:
            self._ops.pop()

    def binary_values(self, op: str, lt: Any, rtp: Any, left: str, right: str) -> str:
        text = super().binary_values(op, lt, rtp, left, right)
        if (
            op not in _PY_OPERATORS
            or "float" not in (lt.base, rtp.base)
            or not self._ops
            or not self._traced()
        ):
            return text
        node, mask = self._ops[-1]
        shape = super().binary_values(op, lt, rtp, "A", "B")
        if shape == f"(A {op} B)":
            fn = f"T.{_PY_OPERATORS[op]}"
        elif shape.startswith("rt.") and shape.endswith("(A, B)"):
            fn = shape[: -len("(A, B)")]
        else:
            return text
        sid = self.site("op", node, op, node)
        return f"T.o(S, {sid}, {mask}, {fn}, {left}, {right})"

    def builtin_call(self, e: A.Call, ov: Any, mask: str | None) -> str:
        text = super().builtin_call(e, ov, mask)
        m = _CALL_PREFIX.match(text)
        if (
            m is None
            or not text.endswith(")")
            or ov.name in _SAFE_BUILTINS
            or not self._traced()
            or self.type_of(e).base != "float"
        ):
            return text
        sid = self.site("op", e, ov.name, e)
        return f"T.o(S, {sid}, {mask}, rt.{m.group(1)}, {text[m.end() :]}"


# ---------------------------------------------------------------------------------------------
# Tracers
# ---------------------------------------------------------------------------------------------

# Operations that make a first NaN or Inf, and what to do about each (the --nan help line).
HELP = {
    "0/0": "both sides of the division are zero here: guard the denominator (max(d, 1e-6)) or "
    "handle the degenerate case first",
    "division by zero": "the denominator is zero here: guard it (max(d, "
    "1e-6)) or test it before dividing",
    "sqrt of a negative": "the argument is negative here (rounding can push a difference of "
    "squares below zero): use sqrt(max(x, 0.0))",
    "log of a negative": "the argument is negative here: clamp it above zero (max(x, 1e-6))",
    "log of zero": "the argument is zero here (the result is -inf): clamp it above zero (max(x, "
    "1e-6))",
    "normalize of a zero vector": "the vector is zero here (the light sits on the surface point, "
    "or two points coincide): guard the zero vector, e.g. test "
    "dot(v, v) > 0.0 before normalizing",
    "inversesqrt(0)": "the argument is zero here: add a small epsilon or test it first",
    "inversesqrt of a negative": "the argument is negative here: use inversesqrt(max(x, 1e-12))",
    "pow of a negative base": "pow(x, y) is undefined for x < 0 (GPUs give NaN): use pow(max(x, "
    "0.0), y), or pow(abs(x), y) with the sign put back",
    "asin or acos outside [-1, 1]": "clamp the argument to [-1, 1] (rounding can push a dot "
    "product of unit vectors past 1)",
    "mod by zero": "the divisor is zero here: guard it",
    "overflow": "the value exceeds the float32 range (3.4e38): scale the computation down or "
    "clamp its inputs",
    "an Inf or NaN operand": "an operand was already Inf or NaN (a constant or an input): "
    "check where it comes from",
    "a non-finite value": "the value was Inf or NaN without an operation that made it (a "
    "constant out of "
    "range?): check the constant",
}
OPERATIONS = list(HELP)
_CODE = {name: i for i, name in enumerate(OPERATIONS)}
_NAME_OPS = {
    "sqrt": "sqrt of a negative",
    "asin": "asin or acos outside [-1, 1]",
    "acos": "asin or acos outside [-1, 1]",
    "normalize": "normalize of a zero vector",
}


def _lanes_any(x: np.ndarray, lanes: int) -> np.ndarray:
    """bool (lanes,): any component of x (lane axis last, size lanes or 1) is true."""
    if x.ndim > 1:
        x = np.asarray(x.reshape(-1, x.shape[-1]).any(axis=0))
    return np.broadcast_to(x, (lanes,))


def _bad(v: Any, lanes: int) -> np.ndarray | None:
    """bool (lanes,) where the value holds NaN or Inf; None when it holds none (the fast path:
    one sum, which is finite exactly when... every term is, unless it overflows: then the exact
    test)."""
    if isinstance(v, Struct):
        out = None
        for f in v.fields.values():
            b = _bad(f, lanes)
            if b is not None:
                out = b if out is None else out | b
        return out
    if isinstance(v, (tuple, list)):
        out = None
        for f in v:
            b = _bad(f, lanes)
            if b is not None:
                out = b if out is None else out | b
        return out
    if (
        not isinstance(v, np.ndarray)
        or v.dtype.kind != "f"
        or math.isfinite(np.add.reduce(v, axis=None))
    ):
        return None
    fin = np.isfinite(v)
    if fin.all():
        return None
    return _lanes_any(~fin, lanes)


def _at(x: Any, idx: np.ndarray) -> Any:
    """The lanes idx of a value (a lane-uniform value broadcasts)."""
    if not isinstance(x, np.ndarray) or x.ndim == 0:
        return np.asarray(x)
    if x.shape[-1] == 1:
        return np.broadcast_to(x, x.shape[:-1] + (len(idx),))
    return x[..., idx]


def classify(name: str, args: tuple, lanes: int) -> np.ndarray:
    """Operation codes (index into OPERATIONS) per lane for an operation `name` (an operator
    symbol or a built-in) whose result is NaN/Inf in these `lanes` (args restricted to them)."""
    args = tuple(np.asarray(a) for a in args)
    fa = [a for a in args if a.dtype.kind == "f"]
    out = np.full(lanes, _CODE["overflow"], np.int16)
    bad_in = np.zeros(lanes, bool)
    for a in fa:
        bad_in |= _lanes_any(~np.isfinite(a), lanes)

    def where(cond, op):
        np.copyto(out, _CODE[op], where=np.broadcast_to(cond, (lanes,)) & ~bad_in)

    x = fa[0] if fa else None
    if name in ("/", "truediv", "div") and len(args) == 2:
        a, b = args
        where(_lanes_any(b == 0, lanes), "division by zero")
        where(_lanes_any((a == 0) & (b == 0), lanes), "0/0")
    elif name in _NAME_OPS and x is not None:
        where(np.ones(lanes, bool), _NAME_OPS[name])
    elif name in ("log", "log2") and x is not None:
        where(_lanes_any(x == 0, lanes), "log of zero")
        where(_lanes_any(x < 0, lanes), "log of a negative")
    elif name == "inversesqrt" and x is not None:
        where(_lanes_any(x == 0, lanes), "inversesqrt(0)")
        where(_lanes_any(x < 0, lanes), "inversesqrt of a negative")
    elif name in ("pow", "pow_const") and x is not None:
        where(_lanes_any(x < 0, lanes), "pow of a negative base")
    elif name == "mod" and len(fa) == 2:
        where(_lanes_any(fa[1] == 0, lanes), "mod by zero")
    np.copyto(out, _CODE["an Inf or NaN operand"], where=bad_in)
    return out


class LaneTracer:
    """Where each lane's first NaN or Inf appeared: `origin[lane]` (a site, -1 for none) and
    `operation[lane]` (an index into OPERATIONS). Hooks as the module docstring lists."""

    add, sub, mul, truediv = operator.add, operator.sub, operator.mul, operator.truediv

    def __init__(self, lanes: int, sites: list[Site]) -> None:
        self.lanes = lanes
        self.sites = sites
        self.origin = np.full(lanes, -1, np.int32)
        self.operation = np.full(lanes, -1, np.int16)
        self.pending = np.full(lanes, -1, np.int32)
        self.pending_op = np.full(lanes, -1, np.int16)
        self.pending_depth = np.zeros(lanes, np.int32)
        self.n_pending = 0
        self.depth = 0
        self.active: np.ndarray | None = None  # run lanes the current call is made for (None: all)
        self._ids: dict[int, tuple[Any, np.ndarray]] = {}

    # -- lanes -------------------------------------------------------------------------------------
    def ids(self, S: Any) -> np.ndarray:
        """The run's lane numbers of the lanes of state S (compacted states are subsets)."""
        got = self._ids.get(id(S))
        if got is None or got[0] is not S:
            parent = S.__dict__.get("parent")
            ids = np.arange(S.lanes) if parent is None else self.ids(parent)[S.__dict__["idx"]]
            got = self._ids[id(S)] = (S, ids)
        return got[1]

    def act(self, S: Any, mask: Any) -> np.ndarray | None | bool:
        """Active lanes of S: None (all), False (none) or a bool (S.lanes,) array."""
        if mask is not None:
            if mask.shape[-1] == 1:
                if not mask[0]:
                    return False
                mask = None
        if self.active is not None:
            a = self.active[self.ids(S)]
            return a if mask is None else a & mask
        return mask

    def _select(self, S: Any, mask: Any, lanes: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
        """(local lane indices, run lane numbers) of the active lanes among `lanes` (None: all)."""
        a = self.act(S, mask)
        if a is False:
            return np.zeros(0, np.intp), np.zeros(0, np.intp)
        sel = lanes if a is None else (a if lanes is None else lanes & a)
        local = np.arange(S.lanes) if sel is None else np.flatnonzero(sel)
        return local, self.ids(S)[local]

    # -- origins -----------------------------------------------------------------------------------
    def _written(self, S: Any, site: int, mask: Any, value: Any) -> None:
        bad = _bad(value, S.lanes)
        if bad is None:
            if self.n_pending:
                self._drop(S, mask)
            return
        _, ids = self._select(S, mask, bad)
        ids = ids[self.origin[ids] < 0]
        if len(ids):
            cand = self.pending[ids]
            has = cand >= 0
            self.origin[ids] = np.where(has, cand, site)
            self.operation[ids] = np.where(has, self.pending_op[ids], _CODE["a non-finite value"])
            self.n_pending -= int(np.count_nonzero(has))
            self.pending[ids] = -1
        if self.n_pending:
            self._drop(S, mask)

    def _drop(self, S: Any, mask: Any) -> None:
        """Candidates of this call depth or deeper are dropped at a finite write."""
        _, ids = self._select(S, mask, None)
        ids = ids[(self.pending[ids] >= 0) & (self.pending_depth[ids] >= self.depth)]
        if len(ids):
            self.pending[ids] = -1
            self.n_pending -= len(ids)

    def o(self, S: Any, site: int, mask: Any, fn: Any, *args: Any) -> Any:
        r = fn(*args)
        bad = _bad(r, S.lanes)
        if bad is not None:
            local, ids = self._select(S, mask, bad)
            new = (self.origin[ids] < 0) & (self.pending[ids] < 0)
            if new.any():
                local, ids = local[new], ids[new]
                name = self.sites[site].name
                name = name if name in _PY_OPERATORS else getattr(fn, "__name__", name)
                self.pending[ids] = site
                self.pending_op[ids] = classify(name, tuple(_at(a, local) for a in args), len(ids))
                self.pending_depth[ids] = self.depth
                self.n_pending += len(ids)
        return r

    # -- steps -------------------------------------------------------------------------------------
    def a(self, S: Any, site: int, mask: Any, value: Any) -> None:
        self._written(S, site, mask, value)

    def r(self, S: Any, site: int, mask: Any, value: Any) -> Any:
        self._written(S, site, mask, value)
        return value

    def b(self, S: Any, site: int, mask: Any, cond: Any) -> Any:
        return cond

    def u(self, S: Any, site: int, mask: Any, value: Any) -> Any:
        return value

    def e(self, S: Any, site: int, mask: Any) -> None:
        pass

    le = li = lx = e

    def call(self, S: Any, site: int, mask: Any, f: Any, call_mask: Any, *args: Any) -> Any:
        for a in args:
            if _bad(a, S.lanes) is not None:
                self._written(S, site, mask, a)
        saved = self.active
        if call_mask is None and mask is not None:
            # a call made once for every lane (uniform arguments) inside a masked region: the
            # callee's lanes are active only where the caller's were
            a = self.act(S, mask)
            g = np.zeros(self.lanes, bool)
            if a is not False:
                g[self.ids(S) if a is None else self.ids(S)[a]] = True
            self.active = g
        self.depth += 1
        try:
            return f(S, call_mask, *args)
        finally:
            self.depth -= 1
            self.active = saved


def lane_value(v: Any, i: int) -> Any:
    """Lane i of a value (a copy): arrays lose their lane axis, structs keep their fields."""
    if isinstance(v, Struct):
        return v.map(lambda x: lane_value(x, i))
    if isinstance(v, tuple):  # (a chain's base and constants: sum_chains.chain_call_args)
        return tuple(lane_value(x, i) for x in v)
    if isinstance(v, np.ndarray) and v.ndim:
        return np.array(v[..., i if v.shape[-1] > 1 else 0])
    return np.asarray(v)


@dataclass
class Record:
    """One step of the probed lane: its site, call depth, the value (lane i only) and, for loop
    markers, `what` ("start", "iteration", "end") and `count`."""

    site: int
    depth: int
    value: Any = None
    what: str = ""
    count: int = 0


class PixelTracer(LaneTracer):
    """A LaneTracer that also records the steps of one lane (`lane`, a lane of the run)."""

    def __init__(self, lanes: int, sites: list[Site], lane: int) -> None:
        super().__init__(lanes, sites)
        self.lane = lane
        self.records: list[Record] = []
        self.truncated = 0  # steps not recorded past MAX_STEPS
        self._loops: list[list] = []  # [iterations, depth, left] of each loop the lane is in

    def on(self, S: Any, mask: Any) -> int | None:
        """The probed lane's index in S when it is active here, else None."""
        ids = self.ids(S)
        pos = (
            self.lane if S.__dict__.get("parent") is None else int(np.searchsorted(ids, self.lane))
        )
        if pos >= len(ids) or ids[pos] != self.lane:
            return None
        if self.active is not None and not self.active[self.lane]:
            return None
        if mask is not None and not mask[pos if mask.shape[-1] > 1 else 0]:
            return None
        return pos

    def _record(self, rec: Record) -> None:
        if len(self.records) < MAX_STEPS:
            self.records.append(rec)
        else:
            self.truncated += 1

    def _step(self, S: Any, site: int, mask: Any, value: Any) -> None:
        i = self.on(S, mask)
        if i is not None:
            self._record(
                Record(site, self.depth, lane_value(value, i) if value is not None else None)
            )

    def _leave(self, site: int, depth: int) -> None:
        """The lane left its innermost loop (break), its call's loops (return) or every loop
        (discard): the unmasked step of an induction variable no longer applies to it."""
        name = self.sites[site].name
        if name == "break":
            if self._loops:
                self._loops[-1][2] = True
            return
        for loop in self._loops:
            if name == "discard" or loop[1] == depth:
                loop[2] = True

    def a(self, S, site, mask, value):
        super().a(S, site, mask, value)
        if not (self.sites[site].loop_step and self._loops and self._loops[-1][2]):
            self._step(S, site, mask, value)

    def r(self, S, site, mask, value):
        if self.on(S, mask) is not None:
            self._leave(site, self.depth)
        self._step(S, site, mask, value)
        return super().r(S, site, mask, value)

    def b(self, S, site, mask, cond):
        self._step(S, site, mask, cond)
        return cond

    def u(self, S, site, mask, value):
        self._step(S, site, mask, value)
        return value

    def e(self, S, site, mask):
        if self.on(S, mask) is not None and self.sites[site].name in ("break", "discard"):
            self._leave(site, self.depth)
        self._step(S, site, mask, None)

    def le(self, S, site, mask):
        if self.on(S, mask) is not None:
            self._loops.append([0, self.depth, False])
            self._record(Record(site, self.depth, what="start"))

    def li(self, S, site, mask):
        if self.on(S, mask) is not None and self._loops:
            self._loops[-1][0] += 1
            self._record(Record(site, self.depth, what="iteration", count=self._loops[-1][0]))

    def lx(self, S, site, mask):
        if self.on(S, mask) is not None and self._loops:
            self._record(Record(site, self.depth, what="end", count=self._loops.pop()[0]))

    def call(self, S, site, mask, f, call_mask, *args):
        i = self.on(S, mask)
        if i is not None:
            self._record(Record(site, self.depth, [lane_value(a, i) for a in args]))
        return super().call(S, site, mask, f, call_mask, *args)
