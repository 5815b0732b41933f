"""Value analysis: the sign and bounds of an expression's value (`ValueRanges.value_range`).

An interval (lo, hi; None for unbounded) and, when the value can be negative, a *witness*: the
sub-expression that makes it so (a dot product of two different vectors, a difference, a
negation, sin/cos, a reflect/refract/cross result, a negative constant). Unknown values (a
parameter, a user function's result) have no witness: rules report "can be negative" only with
one. Dot products of different vectors are taken as cosines in [-1, 1] (lighting code dots unit
vectors), so `1.0 - max(dot(n, v), 0.0)` is known to be >= 0. The pixel's coordinate over the
viewport's size (`fragCoord / iResolution.xy` in mainImage) is in [0, 1). A variable's value is
the one assigned by its last write before the use when that write is on every path to the use
(else unknown: `FunctionFacts.reaching_value`).

`ValueRanges` is a mixin of `glslcheck.semantics.analysis.dataflow.FunctionFacts`, whose value keys
and reaching definitions it reads.
"""

from __future__ import annotations

import math

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ..model import Constructor

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

    from ..model import Model, Symbol

Range = tuple  # (lo: float | None, hi: float | None, witness: tuple[str, node] | None)

# below 1: the most a pixel's centre over the viewport's size reaches ((w - 0.5) / w for any
# width up to 2^14), so that fract() of it and mod() by 1 or more are known to change nothing
BELOW_ONE = 1.0 - 2.0**-15

NONNEGATIVE_UNIFORMS = frozenset(
    {
        "iTime",
        "iTimeDelta",
        "iFrameRate",
        "iFrame",
        "iChannelTime",
        "iChannelResolution",
        "iResolution",
        "iDate",
        "iSampleRate",
    }
)


class ValueRanges:
    """The sign analysis of one function's expressions (cached per node)."""

    model: Model
    _ranges: dict[int, Range]

    if TYPE_CHECKING:  # defined by dataflow.FunctionFacts, the one subclass

        def reaching_value(
            self, ident: A.Identifier, sym: Symbol, as_computed: bool = False
        ) -> Any: ...
        def key(self, e: Any) -> Any: ...
        def writes_to(self, sym: Symbol) -> list: ...

    def value_range(self, e: Any, depth: int = 0) -> tuple:
        """(lo, hi, witness) of an expression; lo/hi None when unbounded; witness is None or
        (reason, node) when the value can be negative for a reason the rules can name."""
        i = id(e)
        r = self._ranges.get(i)
        if r is None:
            r = self._range(e, depth)
            self._ranges[i] = r
        return r

    def _range(self, e: Any, depth: int) -> tuple:
        unknown = (None, None, None)
        if depth > 24:
            return unknown
        value = self.model.const_value(e)
        nums = numbers(value)
        if nums:
            lo, hi = min(nums), max(nums)
            return (lo, hi, ("a negative constant", e) if lo < 0 else None)
        rec = lambda x: self.value_range(x, depth + 1)  # noqa: E731
        t = type(e)
        if t is A.Identifier:
            sym = self.model.symbol_of(e)
            if sym is None:
                return unknown
            if sym.kind == "uniform":
                return (0.0, None, None) if sym.name in NONNEGATIVE_UNIFORMS else unknown
            if sym.kind == "local":
                v = self.reaching_value(e, sym)
                return rec(v) if v is not None else unknown
            return unknown
        if t is A.Field:
            if self.model.is_swizzle(e):
                return rec(e.base)
            return unknown
        if t is A.Index:
            base_t = self.model.type_of(e.base)
            return (
                rec(e.base)
                if getattr(base_t, "is_vector", False) or getattr(base_t, "is_matrix", False)
                else unknown
            )
        if t is A.Unary:
            if e.op == "+":
                return rec(e.operand)
            if e.op == "-":
                lo, hi, why = rec(e.operand)
                nlo = -hi if hi is not None else None
                nhi = -lo if lo is not None else None
                if nlo is not None and nlo >= 0:
                    return (nlo, nhi, None)
                return (nlo, nhi, ("a negation", e))
            return unknown
        if t is A.Binary:
            return self._binary_range(e, rec)
        if t is A.Ternary:
            return _join(rec(e.then), rec(e.else_))
        if t is A.Call:
            return self._call_range(e, rec)
        return unknown

    def _binary_range(self, e: A.Binary, rec) -> tuple:
        op = e.op
        a, b = rec(e.left), rec(e.right)
        (alo, ahi, aw), (blo, bhi, bw) = a, b
        if op == "+":
            lo = _add(alo, blo)
            hi = _add(ahi, bhi)
            return (lo, hi, None if _nonneg(lo) else (aw or bw))
        if op == "-":
            lo = _sub(alo, bhi)
            hi = _sub(ahi, blo)
            if _nonneg(lo):
                return (lo, hi, None)
            return (lo, hi, aw or ("a difference", e))
        if op == "*":
            if self.key(e.left) == self.key(e.right):  # x * x
                return (
                    0.0,
                    None if alo is None or ahi is None else max(alo * alo, ahi * ahi),
                    None,
                )
            if _nonneg(alo) and _nonneg(blo):
                return (alo * blo, _mul(ahi, bhi), None)
            if None not in (alo, ahi, blo, bhi):
                ps = [alo * blo, alo * bhi, ahi * blo, ahi * bhi]
                lo, hi = min(ps), max(ps)
                return (lo, hi, None if lo >= 0 else (aw or bw))
            return (None, None, aw or bw)
        if op == "/":
            if self._frag_fraction(e):
                return (0.0, BELOW_ONE, None)
            if _nonneg(alo) and blo is not None and blo > 0:
                return (0.0, None, None)
            return (None, None, aw or bw)
        return (None, None, None)

    def _frag_fraction(self, e: A.Binary) -> bool:
        """`fragCoord / iResolution.xy` (or one component over the same one): a pixel's centre
        over the viewport's size, in [0, 1) (`fragCoord` being mainImage's, never written)."""
        model = self.model
        left, right = e.left, e.right
        if type(right) is not A.Field or not model.is_swizzle(right):
            return False
        res = model.symbol_of(right.base)
        if res is None or res.kind != "uniform" or res.name != "iResolution":
            return False
        lsw: tuple[int, ...] = (0, 1)  # fragCoord itself: its x and y
        if type(left) is A.Field and model.is_swizzle(left):
            lsw, left = tuple(model.swizzle_indices(left)), left.base
        sym = model.symbol_of(left) if type(left) is A.Identifier else None
        if sym is None or not self._frag_coord(sym):
            return False
        rsw = tuple(model.swizzle_indices(right))
        return lsw == rsw

    def _frag_coord(self, sym: Symbol) -> bool:
        """`sym` is the pixel's coordinate: gl_FragCoord, or mainImage's second parameter when
        the function never writes it."""
        if sym.kind == "builtin-var":
            return sym.name == "gl_FragCoord"
        fn = getattr(self, "symbol", None)
        if sym.kind != "param" or fn is None or fn.name != "mainImage":
            return False
        node = getattr(self, "definition", None)
        params = node.proto.params if node is not None else []
        return (
            len(params) == 2 and self.model.symbol_of(params[1]) is sym and not self.writes_to(sym)
        )

    def _call_range(self, e: A.Call, rec) -> tuple:
        target = self.model.call_target(e)
        if isinstance(target, Constructor):
            if not e.args:
                return (None, None, None)
            return _join(*(rec(a) for a in e.args))
        if not isinstance(target, B.Overload):
            return (None, None, None)
        name, args = e.callee, e.args
        if name == "dot":
            if self.key(args[0]) == self.key(args[1]):
                return (0.0, None, None)
            return (-1.0, 1.0, ("a dot product of two different vectors", e))
        if name in ("length", "distance", "sqrt", "inversesqrt", "exp", "exp2", "pow"):
            return (0.0, None, None)
        if name == "abs":
            lo, hi, _ = rec(args[0])
            return (0.0, None if lo is None or hi is None else max(abs(lo), abs(hi)), None)
        if name in ("smoothstep", "step", "fract"):
            return (0.0, 1.0, None)
        if name in ("sin", "cos"):
            return (-1.0, 1.0, (f"{name}() is negative over half its period", e))
        if name in ("tan", "asin", "atan", "sinh", "tanh", "sign", "dFdx", "dFdy"):
            return (None, None, (f"{name}() can be negative", e))
        if name in ("reflect", "refract", "cross", "faceforward", "normalize"):
            return (
                -1.0 if name == "normalize" else None,
                1.0 if name == "normalize" else None,
                (f"the components of {name}() can be negative", e),
            )
        if name == "max":
            (alo, ahi, aw), (blo, bhi, bw) = rec(args[0]), rec(args[1])
            known = [x for x in (alo, blo) if x is not None]
            lo = max(known) if known else None  # max(a, b) >= a and >= b
            hi = None if ahi is None or bhi is None else max(ahi, bhi)
            if _nonneg(lo):
                return (lo, hi, None)
            # negative only when both are: name a reason only when both sides have one
            return (lo, hi, aw if aw is not None and bw is not None else None)
        if name == "min":
            (alo, ahi, aw), (blo, bhi, bw) = rec(args[0]), rec(args[1])
            lo = None if alo is None or blo is None else min(alo, blo)
            hi = None
            if ahi is not None or bhi is not None:
                hi = min(x for x in (ahi, bhi) if x is not None)
            return (lo, hi, None if _nonneg(lo) else (aw or bw))
        if name == "clamp":
            _, _, xw = rec(args[0])
            llo, _, lw = rec(args[1])
            _, hhi, _ = rec(args[2])
            if _nonneg(llo):
                return (llo, hhi, None)
            return (llo, hhi, lw or xw)
        if name == "mix":
            return _join(rec(args[0]), rec(args[1]))
        if name == "mod":
            lo, hi, _ = rec(args[1])
            return (0.0, hi, None) if lo is not None and lo > 0 else (None, None, None)
        return (None, None, None)

    def negative_witness(self, e: Any) -> tuple[str, Any] | None:
        """(reason, node) when `e` can be negative for a nameable reason, else None."""
        lo, _, why = self.value_range(e)
        if _nonneg(lo):
            return None
        return why


def numbers(value: Any) -> list[float]:
    if isinstance(value, bool) or value is None:
        return []
    if isinstance(value, (int, float)):
        return [float(value)] if math.isfinite(value) else []
    if isinstance(value, tuple):
        out: list[float] = []
        for v in value:
            sub = numbers(v)
            if not sub:
                return []
            out += sub
        return out
    return []


def _nonneg(x: float | None) -> bool:
    return x is not None and x >= 0


def _add(a, b):
    return None if a is None or b is None else a + b


def _sub(a, b):
    return None if a is None or b is None else a - b


def _mul(a, b):
    return None if a is None or b is None else a * b


def _join(*ranges: tuple) -> tuple:
    los = [r[0] for r in ranges]
    his = [r[1] for r in ranges]
    lo = None if any(x is None for x in los) else min(los)
    hi = None if any(x is None for x in his) else max(his)
    why = None if _nonneg(lo) else next((r[2] for r in ranges if r[2] is not None), None)
    return (lo, hi, why)
