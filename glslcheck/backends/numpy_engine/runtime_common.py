"""The Runtime's common, packing, geometric, vector-relational and derivative built-ins."""

from __future__ import annotations

from typing import Any

import numpy as np

from .llvmpipe_reference import keeps_shape
from .runtime_state import RuntimeState
from .runtime_values import BOOL, I32, U32, GLSLRuntimeError, where


class CommonFunctions(RuntimeState):
    """GLSL's common, packing, geometric, relational and derivative functions (a mixin of
    Runtime)."""

    # ------------------------------------------------------------------ common
    def abs(self, x: Any) -> np.ndarray:
        """abs for float and int (abs(INT_MIN) == INT_MIN)."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        return np.abs(x)

    def sign(self, x: Any) -> np.ndarray:
        """1, -1 or 0 (sign(-0.0) == +0.0, sign(NaN) == 0, as llvmpipe); int too."""
        x = self._num(x) if not isinstance(x, np.ndarray) else x
        if x.dtype.kind == "i":
            return np.sign(x)
        one = x.dtype.type(1)
        return np.where(x > 0, one, np.where(x < 0, -one, x.dtype.type(0)))

    def floor(self, x: Any) -> np.ndarray:
        return np.floor(self._f(x))

    def ceil(self, x: Any) -> np.ndarray:
        return np.ceil(self._f(x))

    def trunc(self, x: Any) -> np.ndarray:
        return np.trunc(self._f(x))

    def round(self, x: Any) -> np.ndarray:
        """Half-way cases go to even on llvmpipe (round(2.5) == 2, round(-2.5) == -2)."""
        return np.rint(self._f(x))

    def roundEven(self, x: Any) -> np.ndarray:
        return np.rint(self._f(x))

    def fract(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return x - np.floor(x)

    def mod(self, x: Any, y: Any) -> np.ndarray:
        """``x - y * floor(x / y)`` in the float dtype (not np.mod/np.fmod)."""
        x, y = self._f(x), self._f(y)
        return x - y * np.floor(x / y)

    def modf(self, x: Any) -> tuple[np.ndarray, np.ndarray]:
        """Returns ``(fractional part, integer part)``, both with the sign of x; the
        transpiler assigns the second to the ``out`` argument."""
        x = self._f(x)
        i = np.trunc(x)
        return x - i, i

    def min_(self, a: Any, b: Any) -> np.ndarray:
        """``min``; a NaN operand yields the other operand (IEEE minNum, as llvmpipe)."""
        a, b = self._pair(a, b)
        return np.fmin(a, b) if a.dtype.kind == "f" else np.minimum(a, b)

    def max_(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._pair(a, b)
        return np.fmax(a, b) if a.dtype.kind == "f" else np.maximum(a, b)

    def clamp(self, x: Any, lo: Any, hi: Any) -> np.ndarray:
        """``min(max(x, lo), hi)`` exactly (lo > hi gives hi; NaN x gives lo)."""
        return self.min_(self.max_(x, lo), hi)

    def mix(self, x: Any, y: Any, a: Any, form: str | tuple | None = None) -> np.ndarray:
        """``x*(1-a) + y*a``; with a bool ``a`` selects y where a is true.

        In float32 (llvmpipe) mode, ``form`` is the formula Mesa's nir_lower_flrp picks for this
        call (llvmpipe has no FFMA; :func:`nir_fold.mix_form` decides from the operands the
        compiler knows), or ``"select"`` for a weight NIR sees as a bool converted to float
        (``step()``: nir_opt_algebraic's bcsel, y where a is 1, else x): ``"strict"``
        ``x*(1-a) + y*a`` (a constant ``a``, or ``y`` = +-1),
        ``"fast"`` ``x + a*(y-x)`` (run-time ``a``: measured bit for bit), ``"one"`` /
        ``"minus_one"`` ``(x - a) + y*a`` / ``(x + a) + y*a`` for a constant ``x`` of +1 / -1.
        None: :meth:`_flrp_form` guesses it from the operands. A tuple: one form per component
        (llvmpipe lowers a vector mix to scalars first). float64 and float16 keep the GLSL
        formula."""
        if isinstance(a, np.ndarray) and a.dtype == BOOL:
            x, y = self._pair(x, y)
            return where(a, y, x)
        x, y, a = self._f(x), self._f(y), self._f(a)
        if self.lp is not None:
            if isinstance(form, tuple):
                parts = [
                    self.mix(_row(x, i), _row(y, i), _row(a, i), f) for i, f in enumerate(form)
                ]
                return np.stack(np.broadcast_arrays(*parts))
            if form is None:
                form = self._flrp_form(x, y, a)
            if form == "select":  # a b2f weight: 0 or 1, so y exactly where it is 1
                return where(self._selects_y(a), y, x)
            if form == "fast":  # compiled (jit.py) where that pays; the same bits
                return self.lp.builtin("_mix", self._mix_fast)(x, y, a)
            if form in ("one", "minus_one"):
                r = (x - a) if form == "one" else (x + a)
                return r + y * a
        r = self.fmul(x, self._1 - a)  # a constant a of 0 or 1 drops the other side (fmul)
        t = self.fmul(y, a)
        if r.shape == t.shape and r.ndim:  # the sum in r's buffer
            return np.add(r, t, out=r)
        return r + t

    def _mix_fast(self, x: np.ndarray, y: np.ndarray, a: np.ndarray) -> np.ndarray:
        """mix's "fast" form in float32: ``x + a*(y - x)`` in every lane, a weight of 0 or 1
        included (``x + (y - x)`` need not be y; a NaN on either side stays)."""
        r = np.subtract(y, x)
        r = np.multiply(a, r, out=r if keeps_shape(r, a) else None)
        return np.add(x, r, out=r if keeps_shape(r, x) else None)

    def _selects_y(self, a: np.ndarray) -> np.ndarray:
        """``a == 1`` for a b2f weight, made once for the mixes that share the weight (a
        struct's fields selected field by field): the last one is kept, as one tuple."""
        last = self._last_weight
        if last[0] is a:
            return last[1]
        one = a == self._1
        self._last_weight = (a, one)
        return one

    def _mix_selects(self, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """What the "select" form (a b2f weight, 0 or 1) takes: (a == 1: y only, a == 0: x
        only), per lane and component."""
        return a == self._1, a == self._0

    def mix_reads(self, a: Any, side: int, form: str | None) -> np.ndarray | None:
        """The lanes in which ``mix(x, y, a, form)`` reads its argument ``side`` (0: x, 1: y), as
        a bool array over the lanes, or None for every lane: a bool weight and the float32
        "select" form ignore the other side (:meth:`_mix_selects`), NaN included; the other
        forms, and float64 or float16 renders, read both sides everywhere. For the
        transpiler's dead-lane regions (transpile/dead_lanes.py)."""
        if not isinstance(a, np.ndarray) or a.ndim == 0 or a.shape[-1] == 1:
            return None  # (one value for every lane: nothing to gain per lane)
        if a.dtype == BOOL:
            reads = a if side == 1 else ~a
        elif form == "select" and self.lp is not None and a.dtype == np.float32:
            one, zero = self._mix_selects(a)
            reads = ~(zero if side == 1 else one)
        else:
            return None
        return np.asarray(
            reads if reads.ndim == 1 else reads.any(axis=tuple(range(reads.ndim - 1)))
        )

    def _flrp_form(self, x: np.ndarray, y: np.ndarray, a: np.ndarray) -> str:
        """The lowering ``convert_flrp_instruction`` (Mesa nir_lower_flrp.c; llvmpipe sets
        lower_ffma32, so no FMA form) picks for ``mix(x, y, a)``, in its order: x and y both
        constants whose exponents differ by at most 11 -> fast; x a constant of all +1 / -1 ->
        one / minus_one; y a constant of all +1 or all -1 -> strict; a constant -> strict; else
        fast. For direct calls only: transpiled code passes the form :func:`nir_fold.mix_form`
        decides from the source (this run-time guess depends on the lane count). "Constant" is
        :meth:`_const` (lane-uniform and not a uniform input, as for :meth:`fmul`) with
        ``fold_constants``; direct calls count a lane-uniform ``a`` only. Approximation: a value
        computed from uniforms only (``sin(iTime)``) counts as a constant here, where Mesa sees a
        run-time value."""
        if not self.fold_constants:
            return "strict" if a.ndim == 0 or a.shape[-1] == 1 else "fast"
        cx, cy = self._const(x) and x.size <= 16, self._const(y) and y.size <= 16
        if cx and cy:
            ex, ey = (
                np.frexp(np.broadcast_arrays(x, y)[0])[1],
                np.frexp(np.broadcast_arrays(y, x)[0])[1],
            )
            if (np.abs(ex - ey) <= 11).all():
                return "fast"
        if cx and (x == self._1).all():
            return "one"
        if cx and (x == -self._1).all():
            return "minus_one"
        if cy and ((y == self._1).all() or (y == -self._1).all()):
            return "strict"
        return "strict" if self._const(a) else "fast"

    def step(self, edge: Any, x: Any) -> np.ndarray:
        """0 where x < edge else 1; NaN gives 0 (llvmpipe computes x >= edge)."""
        return self.step_mask(edge, x).astype(self.F)

    def step_mask(self, edge: Any, x: Any) -> np.ndarray:
        """Where `step(edge, x)` is 1, as bools: ``x >= edge`` (false for NaN)."""
        return self._f(x) >= self._f(edge)

    def mix_b2f(self, x: Any, y: Any, c: Any) -> np.ndarray:
        """``mix(x, y, float(c))`` for the bools ``c`` of a weight NIR sees as b2f (transpile:
        Expressions.b2f_select): in float32 (llvmpipe) nir_opt_algebraic's select, y where c,
        the other side ignored (NaN included), as `mix`'s "select" form; float64 and float16
        renders keep mix's formula."""
        if self.lp is None:
            return self.mix(x, y, self._f(c), "select")  # (float(c): _f as to_float)
        return where(c, self._f(y), self._f(x))

    def smoothstep(self, e0: Any, e1: Any, x: Any) -> np.ndarray:
        """t = clamp((x-e0)/(e1-e0), 0, 1); t*(t*(3-2t)). Equal edges follow the formula
        (0/0 = NaN clamps to 0), as llvmpipe."""
        e0, e1, x = self._f(e0), self._f(e1), self._f(x)
        t = self.clamp((x - e0) / (e1 - e0), self._0, self._1)
        return t * (t * (self._3 - self._2 * t))

    def smoothstep_scaled(self, e0: Any, e1: Any, x: Any, k: np.ndarray) -> np.ndarray:
        """``k * smoothstep(e0, e1, x)`` with the constant k sunk into Mesa's product:
        ``(t*k) * (t*(3-2t))`` (nir_fold.smoothstep_products; k has no zero component)."""
        e0, e1, x = self._f(e0), self._f(e1), self._f(x)
        t = self.clamp((x - e0) / (e1 - e0), self._0, self._1)
        return (t * k) * (t * (self._3 - self._2 * t))

    @staticmethod
    def isnan(x: np.ndarray) -> np.ndarray:
        return np.isnan(x)

    @staticmethod
    def isinf(x: np.ndarray) -> np.ndarray:
        return np.isinf(x)

    def floatBitsToInt(self, x: Any) -> np.ndarray:
        return self._f(x).astype(np.float32).view(I32)

    def floatBitsToUint(self, x: Any) -> np.ndarray:
        return self._f(x).astype(np.float32).view(U32)

    def intBitsToFloat(self, x: Any) -> np.ndarray:
        x = np.asarray(x, dtype=I32) if not isinstance(x, np.ndarray) else x
        f = x.astype(I32).view(np.float32)
        return f if self.F is np.float32 else f.astype(self.F)

    def uintBitsToFloat(self, x: Any) -> np.ndarray:
        x = np.asarray(x, dtype=U32) if not isinstance(x, np.ndarray) else x
        f = x.astype(U32).view(np.float32)
        return f if self.F is np.float32 else f.astype(self.F)

    # ------------------------------------------------------------------ packing
    @staticmethod
    def _pack16(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        return (lo.astype(U32) & U32(0xFFFF)) | (hi.astype(U32) << U32(16))

    def packSnorm2x16(self, v: np.ndarray) -> np.ndarray:
        """round(clamp(c, -1, 1) * 32767) per component (round half to even). NaN gives -32767
        (0x8001) as on llvmpipe, whose clamp is max-then-min with IEEE maxNum: max(NaN, -1) is
        -1 (measured)."""
        v = self._f(v).astype(np.float32)
        q = np.rint(np.nan_to_num(np.clip(v, -1.0, 1.0), nan=-1.0) * np.float32(32767.0))
        q = q.astype(np.int32).astype(np.int16).view(np.uint16)
        return self._pack16(q[0], q[1])

    def unpackSnorm2x16(self, p: Any) -> np.ndarray:
        p = np.asarray(p).astype(U32)
        lo = (p & U32(0xFFFF)).astype(np.uint16).view(np.int16)
        hi = (p >> U32(16)).astype(np.uint16).view(np.int16)
        v = np.stack([lo, hi]).astype(np.float32) / np.float32(32767.0)
        return np.clip(v, -1.0, 1.0).astype(self.F)

    def packUnorm2x16(self, v: np.ndarray) -> np.ndarray:
        v = self._f(v).astype(np.float32)
        q = np.rint(np.nan_to_num(np.clip(v, 0.0, 1.0), nan=0.0) * np.float32(65535.0))
        q = q.astype(np.uint32)
        return self._pack16(q[0], q[1])

    def unpackUnorm2x16(self, p: Any) -> np.ndarray:
        p = np.asarray(p).astype(U32)
        v = np.stack([p & U32(0xFFFF), p >> U32(16)]).astype(np.float32) / np.float32(65535.0)
        return v.astype(self.F)

    def packHalf2x16(self, v: np.ndarray) -> np.ndarray:
        h = self._f(v).astype(np.float32).astype(np.float16).view(np.uint16)
        return self._pack16(h[0], h[1])

    def unpackHalf2x16(self, p: Any) -> np.ndarray:
        p = np.asarray(p).astype(U32)
        h = np.stack([p & U32(0xFFFF), p >> U32(16)]).astype(np.uint16).view(np.float16)
        return h.astype(self.F)

    # ------------------------------------------------------------------ geometric
    def length(self, x: Any) -> np.ndarray:
        x = self._f(x)
        if x.ndim == 1:
            return np.abs(x)
        d = self.dot(x, x)
        return np.sqrt(d, out=d)

    def distance(self, a: Any, b: Any) -> np.ndarray:
        return self.length(self.sub(self._f(a), self._f(b)))

    def cross(self, a: Any, b: Any) -> np.ndarray:
        a, b = self._f(a), self._f(b)
        return self._stack(
            [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        )

    def normalize(self, x: Any) -> np.ndarray:
        """``x * inversesqrt(dot(x, x))`` (zero vector -> NaN); a float normalizes to sign(x)."""
        x = self._f(x)
        if x.ndim == 1:
            return self.sign(x)
        d = self.dot(x, x)  # a fresh array: sqrt and the reciprocal reuse it
        np.sqrt(d, out=d)
        np.divide(self._1, d, out=d)
        return x * d

    def faceforward(self, n: Any, i: Any, nref: Any) -> np.ndarray:
        n = self._f(n)
        return np.where(self.dot(nref, i) < self._0, n, -n)

    def reflect(self, i: Any, n: Any) -> np.ndarray:
        i, n = self._f(i), self._f(n)
        return i - self._2 * (self.dot(n, i) * n)

    def refract(self, i: Any, n: Any, eta: Any) -> np.ndarray:
        i, n, eta = self._f(i), self._f(n), self._f(eta)
        d = self.dot(n, i)
        k = self._1 - eta * eta * (self._1 - d * d)
        r = eta * i - (eta * d + np.sqrt(k)) * n
        return np.where(k < self._0, self._0, r)

    # ------------------------------------------------------------------ vector relational
    def lessThan(self, a: Any, b: Any) -> np.ndarray:
        return self.lt(a, b)

    def lessThanEqual(self, a: Any, b: Any) -> np.ndarray:
        return self.le(a, b)

    def greaterThan(self, a: Any, b: Any) -> np.ndarray:
        return self.gt(a, b)

    def greaterThanEqual(self, a: Any, b: Any) -> np.ndarray:
        return self.ge(a, b)

    def equal(self, a: Any, b: Any) -> np.ndarray:
        return self.eq(a, b)

    def notEqual(self, a: Any, b: Any) -> np.ndarray:
        return self.ne(a, b)

    @staticmethod
    def any(v: np.ndarray) -> np.ndarray:
        return np.any(v, axis=0)

    @staticmethod
    def all(v: np.ndarray) -> np.ndarray:
        return np.all(v, axis=0)

    @staticmethod
    def not_vec(v: np.ndarray) -> np.ndarray:
        """The built-in ``not(bvec)`` (``not`` is a Python keyword)."""
        return np.logical_not(v)

    # ------------------------------------------------------------------ derivatives
    def _quad_diff(self, v: Any, width: int, axis: int) -> np.ndarray:
        v = self._f(v)
        if v.shape[-1] == 1:
            return np.zeros_like(v)
        n = v.shape[-1]
        if n % width:
            raise ValueError(f"lane count {n} is not a multiple of the tile width {width}")
        height = n // width
        img = v.reshape(v.shape[:-1] + (height, width))
        ax = img.ndim - 2 + axis  # axis 1: x (columns), axis 0: y (rows)
        size = img.shape[ax]
        even = [slice(None)] * img.ndim
        odd = [slice(None)] * img.ndim
        even[ax] = slice(0, size - 1, 2)
        odd[ax] = slice(1, size, 2)
        d = img[tuple(odd)] - img[tuple(even)]
        out = np.repeat(d, 2, axis=ax)
        if size % 2:  # odd size: the last row/column reuses its left/lower neighbour pair
            last = [slice(None)] * img.ndim
            last[ax] = slice(size - 1, size)
            prev = [slice(None)] * img.ndim
            prev[ax] = slice(size - 2, size - 1)
            if size > 1:
                tail = img[tuple(last)] - img[tuple(prev)]
            else:
                tail = np.zeros_like(img[tuple(last)])
            out = np.concatenate([out, tail], axis=ax)
        return out.reshape(v.shape)

    def dFdx(self, v: Any, width: int) -> np.ndarray:
        """Fine x-derivative as llvmpipe: lanes are the rows of a ``width``-wide tile,
        lane = y*width + x with y counted from the bottom (gl_FragCoord order), 2x2 quads start
        at even x and y. ``dFdx(x, y) = v(x|1, y) - v(x&~1, y)``. Tiles of a shader that uses
        derivatives are rendered with llvmpipe's helper column/row at an odd edge (program.py
        `render_tile`), so quads are whole; an odd width seen here anyway (the probe's strips)
        uses the difference to its left neighbour. Lane-uniform values have zero derivative."""
        return self._quad_diff(v, width, 1)

    def dFdy(self, v: Any, width: int) -> np.ndarray:
        """Fine y-derivative: ``v(x, y|1) - v(x, y&~1)``; see :meth:`dFdx`."""
        return self._quad_diff(v, width, 0)

    def fwidth(self, v: Any, width: int) -> np.ndarray:
        return np.abs(self.dFdx(v, width)) + np.abs(self.dFdy(v, width))

    # ------------------------------------------------------------------ unsupported
    @staticmethod
    def texture_unsupported(name: str, line: int | None = None) -> None:
        """Raise for texture lookups, which the NumPy backend does not evaluate."""
        where = f" (line {line})" if line is not None else ""
        raise GLSLRuntimeError(
            f"{name}{where}: texture lookups are not supported by the NumPy backend"
        )


def _row(v: np.ndarray, i: int) -> np.ndarray:
    """Component `i` of a vector value of shape (components, lanes) or (components, 1); a
    scalar (one dimension or none) is every component."""
    return v if v.ndim < 2 else v[i if v.shape[0] > 1 else 0]
