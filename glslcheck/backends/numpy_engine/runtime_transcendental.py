"""The Runtime's angle, trigonometric and exponential built-ins: llvmpipe's algorithms in float32
(LlvmpipeMath), Mesa's own lowerings of atan, asin and acos, and pow's compile-time rewrites.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .llvmpipe_reference import POW_REWRITTEN, daz
from .runtime_state import RuntimeState


class TranscendentalFunctions(RuntimeState):
    """GLSL's angle, trigonometric and exponential functions (a mixin of Runtime)."""

    # ------------------------------------------------------------------ angle & trig
    def radians(self, x: Any) -> np.ndarray:
        return self._f(x) * self.F(math.pi / 180.0)

    def degrees(self, x: Any) -> np.ndarray:
        return self._f(x) * self.F(180.0 / math.pi)

    def sin(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.sin_or_cos(self._f(x), cos=False)
        return np.sin(self._f(x))

    def cos(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.sin_or_cos(self._f(x), cos=True)
        return np.cos(self._f(x))

    def tan(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.tan(self._f(x))
        return np.tan(self._f(x))

    def _asin_expr(self, x: np.ndarray, p0: float, p1: float) -> np.ndarray:
        """Mesa's GLSL built-in (builtin_functions.cpp ``asin_expr``); its constants are float
        literals, so ``M_PI_4f - 1.0f`` is rounded to float32 twice, as in C."""
        F = self.F
        a = np.abs(x)
        c1 = F(F(math.pi / 4) - F(1.0))
        poly = F(math.pi / 2) + a * (c1 + a * (F(p0) + a * F(p1)))
        return self.sign(x) * (F(math.pi / 2) - np.sqrt(self._1 - a) * poly)

    def asin(self, x: Any) -> np.ndarray:
        """Mesa's polynomial asin (|x| > 1 -> NaN through sqrt)."""
        if self.lp is not None:  # compiled (jit.py) where that pays; the same bits
            return self.lp.builtin("_asin", self._asin)(self._f(x))
        return self._asin(x)

    def _asin(self, x: Any) -> np.ndarray:
        return self._asin_expr(self._daz(x), 0.086566724, -0.03102955)

    def acos(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.builtin("_acos", self._acos)(self._f(x))
        return self._acos(x)

    def _acos(self, x: Any) -> np.ndarray:
        return self.F(math.pi / 2) - self._asin_expr(self._daz(x), 0.08132463, -0.02363318)

    # nir_atan's odd polynomial x*c0 + x^3*c1 + ... + x^11*c5 (Mesa 22.3 nir_builtin_builder.c)
    _ATAN_COEFFS = (
        0.9999793128310355,
        -0.3326756418091246,
        0.1938924977115610,
        -0.1173503194786851,
        0.0536813784310406,
        -0.0121323213173444,
    )

    def _daz(self, x: Any) -> np.ndarray:
        """Subnormal operands read as zero in float32 (llvmpipe's DAZ); other modes unchanged."""
        x = self._f(x)
        return daz(x) if self.lp is not None else x

    def _nir_atan(self, v: np.ndarray) -> np.ndarray:
        """Mesa 22.3 ``nir_atan``: x = min(|v|, 1) / max(|v|, 1); the six terms x^(2k+1)*c_k
        (x^3 = x^2*x, x^5 = x^3*x^2, ...) summed left to right; for |v| > 1 the fixup
        ``(t*-2 + pi/2) + t``; then times ``fsign(v)`` (fsign(NaN) = fsign(-0) = 0 on llvmpipe,
        so atan(NaN) = 0 and atan(-0) = +0). The last term is not ``(x^9*x^2)*c5``:
        nir_opt_algebraic's constant reassociation ``(a*b)*#c -> (a*#c)*b`` (a*b used once,
        the rule :mod:`nir_fold` describes) makes it ``(x^9*c5)*x^2``. Bit-exact with llvmpipe
        (measured: tests/gl/test_llvmpipe_math.py)."""
        F = self.F
        a = np.abs(v)
        x = self._daz(np.fmin(a, self._1) / np.fmax(a, self._1))  # FTZ of the quotient
        x2 = x * x
        p = x
        t = x * F(self._ATAN_COEFFS[0])
        for k, cf in enumerate(self._ATAN_COEFFS[1:], 1):
            if k == len(self._ATAN_COEFFS) - 1 and self.lp is not None:
                t = t + (p * F(cf)) * x2  # x^11 is used once only: reassociated
                break
            p = p * x2
            t = t + p * F(cf)
        t = self._daz(t)  # FTZ: a subnormal sum (|v| < 1.2e-38 / 0.99998) is 0 there
        t = np.where(self._1 < a, (t * F(-2.0) + F(math.pi / 2)) + t, t)
        return t * self.sign(v)

    def atan(self, y: Any, x: Any = None) -> np.ndarray:
        """``atan(y_over_x)`` and ``atan(y, x)`` following Mesa's NIR lowering (atan(0, 0) is
        3*pi/4 on llvmpipe: the lowering pretends 0/0 = 1 on the left half-plane)."""
        if self.lp is not None:  # compiled (jit.py) where that pays; the same bits
            if x is None:
                return self.lp.builtin("_atan", self._atan)(self._f(y))
            return self.lp.builtin("_atan2", self._atan)(self._f(y), self._f(x))
        return self._atan(y, x)

    def _atan(self, y: Any, x: Any = None) -> np.ndarray:
        if x is None:
            return self._nir_atan(self._daz(y))
        F = self.F
        y, x = self._daz(y), self._daz(x)
        flip = self._0 >= x
        ax = np.abs(x)
        s = np.where(flip, ax, y)
        t = np.where(flip, y, ax)
        scale = np.where(np.abs(t) >= F(1e18), F(0.25), self._1)
        rcp = self._1 / (t * scale)
        abs_s_over_t = self._daz(np.abs(s * scale) * np.abs(rcp))  # FTZ of the product
        tan = np.where(ax == np.abs(y), self._1, abs_s_over_t)
        arc = flip.astype(F) * F(math.pi / 2) + self._nir_atan(tan)
        return np.where(np.fmin(y, rcp) < self._0, -arc, arc)

    def sinh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self._half * (self.exp(x) - self.exp(-x))

    def cosh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self._half * (self.exp(x) + self.exp(-x))

    def tanh(self, x: Any) -> np.ndarray:
        """(e^x - e^-x)/(e^x + e^-x) with x clamped to [-10, 10] by GLSL clamp (llvmpipe:
        tanh(100) = 1; tanh(NaN) = -1, since clamp(NaN, -10, 10) = -10)."""
        x = self.clamp(self._f(x), self.F(-10.0), self.F(10.0))
        e1, e2 = self.exp(x), self.exp(-x)
        return (e1 - e2) / (e1 + e2)

    def asinh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self.sign(x) * self.log(np.abs(x) + np.sqrt(x * x + self._1))

    def acosh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self.log(x + np.sqrt(x * x - self._1))

    def atanh(self, x: Any) -> np.ndarray:
        x = self._f(x)
        return self._half * self.log((self._1 + x) / (self._1 - x))

    # ------------------------------------------------------------------ exponential
    def pow(self, x: Any, y: Any) -> np.ndarray:
        """``exp2(y * log2(x))`` with llvmpipe's edges: x < 0 -> NaN; x == 0 or x NaN -> 0
        (for every y, including 0, negative and NaN)."""
        x, y = self._f(x), self._f(y)
        if (
            self.fold_constants
            and y.ndim
            and y.shape[-1] == 1
            and y.size <= 4
            and y.flags.writeable
            and all(float(v) in POW_REWRITTEN for v in y.reshape(-1))  # (np.isin: 0.2 ms a call)
            and not np.signbit(y).any()
        ):
            # an exponent the same in every lane (a constant after Mesa's propagation) of 0, 1,
            # 2 or 4: Mesa rewrites pow there (pow_const); as fmul, a uniform input equal to
            # one of these is taken for a constant too
            c = tuple(float(v) for v in y.reshape(-1))
            if not any(c):  # NIR's fpow(a, 0.0) -> 1.0 (measured: pow(0, e) = 1 for a zeroed e)
                return np.ones(np.broadcast_shapes(x.shape, y.shape), dtype=self.F)
            return self.pow_const(x, c if y.ndim > 1 else c[0])
        if self.lp is not None:
            return self.lp.pow(x, daz(y))
        r = np.log2(x)
        one_y = y.size == 1
        if one_y and r.ndim:  # one buffer for every step
            np.multiply(y, r, out=r)
            np.exp2(r, out=r)
        else:
            r = np.exp2(y * r)
        yv = float(y.reshape(-1)[0]) if one_y else 0.0
        if 0.0 < yv < math.inf:
            zero = np.isnan(x)  # exp2(y * log2(0)) = exp2(-inf) is already 0 for y > 0
        else:
            zero = (x == self._0) | np.isnan(x)
        if r.ndim and zero.shape == r.shape:
            np.copyto(r, self._0, where=zero)
            return r
        return np.where(zero, self._0, r)

    def pow_const(self, x: Any, c: Any) -> np.ndarray:
        """``pow(x, c)`` with a compile-time constant exponent ``c`` (a Python float, or a tuple
        of floats for a vector), compiled as Mesa compiles it: per component, an exponent of
        1.0 is ``x``, 2.0 is ``x*x``, 4.0 is ``(x*x)*(x*x)`` (so pow(-0.5, 2.0) = 0.25 where
        the run-time formula gives NaN), +0.0 is 1 except 0 for x == 0 or NaN (``log2(x) * 0``
        folded to 0, then llvmpipe's x == 0 select); any other exponent (-0.0, 0.5, 3.0, ...)
        is the run-time :meth:`pow`."""
        x = self._f(x)
        if isinstance(c, tuple):
            if len(set(c)) == 1 and len({math.copysign(1.0, v) for v in c}) == 1:
                return self.pow_const(x, c[0])
            return np.stack([self.pow_const(x[i], v) for i, v in enumerate(c)])
        if c == 1.0:
            return x
        if c == 2.0:
            return x * x
        if c == 4.0:
            sq = x * x
            return sq * sq
        if c == 0.0 and math.copysign(1.0, c) > 0:
            return np.where((x == self._0) | np.isnan(x), self._0, self._1)
        return self.pow(x, self.F(c))

    def pow_one(self, y: Any) -> np.ndarray:
        """``pow(1.0, y)`` with a constant base of all ones: Mesa's GLSL compiler returns the
        constant 1 (the run-time formula gives NaN for y = +-inf or NaN)."""
        return np.ones_like(self._f(y))

    def exp(self, x: Any) -> np.ndarray:
        """``exp2(x * log2(e))`` (lp_build_exp; a subnormal x is 0 in the product, DAZ)."""
        return self.exp2(self._daz(x) * self.F(1.4426950408889634))

    def log(self, x: Any) -> np.ndarray:
        """``log2(x) * ln(2)`` (lp_build_log_safe)."""
        return self.log2(x) * self.F(0.6931471805599453)

    def exp2(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.exp2(self._f(x))
        return np.exp2(self._f(x))

    def log2(self, x: Any) -> np.ndarray:
        if self.lp is not None:
            return self.lp.log2(self._f(x))
        return np.log2(self._f(x))

    def sqrt(self, x: Any) -> np.ndarray:
        return np.sqrt(self._f(x))

    def inversesqrt(self, x: Any) -> np.ndarray:
        return self._1 / np.sqrt(self._f(x))
