"""llvmpipe's float32 algorithms (gallivm) step by step in NumPy: the reference the NumPy engine
computes sin, cos, tan, exp2, log2 and pow with (LlvmpipeMath), the emulated fused multiply-add
(fma32) and DAZ (daz), and the dispatch of each algorithm to llvmpipe_fast's kernels or
jit.py's compiled ones. Runtime (runtime.py) owns one LlvmpipeMath in float32.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..driver_profile import host_fma
from ..llvmpipe_math import coefficients
from . import jit, llvmpipe_fast

I32 = np.int32
U32 = np.uint32
INT_MIN = -(2**31)


# ---------------------------------------------------------------------------------------------
# llvmpipe's own float32 algorithms (gallivm), step by step.
#
# Mesa 22.3.6 compiles GLSL sin, cos, exp2, log2 (and pow, exp, log built on them) to LLVM IR
# with the code in src/gallium/auxiliary/gallivm/lp_bld_arit.c; the functions below repeat
# each IR instruction in float32 so the NumPy backend gets the same bits (measured bit for bit
# on 400,000 inputs each, subnormals, +-0, +-Inf, NaN and |x| up to 3e38 included:
# tests/numpy/test_llvmpipe_math_gl.py). CPU dependence, recorded where it arises:
#
# - ``lp_build_mad``/``lp_build_fmuladd`` emit ``llvm.fmuladd``, which LLVM fuses into one
#   rounding on a CPU with FMA (x86 FMA3: Haswell and later) and evaluates as a multiply and
#   an add elsewhere. :data:`HOST_FMA` reads the CPU flags; ``Runtime(fma=...)`` overrides.
#   GLSL's own ``a*b + c`` is never fused (llvmpipe does not set NIR's fuse_ffma): only the
#   steps inside these built-ins are.
# - llvmpipe runs shaders with MXCSR DAZ|FTZ (lp_build_fpstate_set_denorms_zero): subnormal
#   operands count as zero inside these algorithms (:func:`daz`).
# - out-of-range float->int conversions inside them (``cvttps2dq``) give INT_MIN on every x86
#   CPU (SSE2 and AVX-512 alike): that is what makes cos(1e10) = 1 there.


HOST_FMA = host_fma()
F32 = np.float32
POW_REWRITTEN = (0.0, 1.0, 2.0, 4.0)  # exponents Mesa's compiler rewrites (Runtime.pow_const)
FLT_MIN = F32(1.17549435e-38)


_BLOCK = 65536  # lanes per pass inside LlvmpipeMath (a render tile, 49152 lanes, is one block)
# up to this many lanes a call checks its fused multiply-adds for midpoints once at the end
# (LlvmpipeMath._fast); above, keeping every float64 sum alive costs more than the checks it saves
DEFER_LANES = 4096


def daz(x: np.ndarray) -> np.ndarray:
    """Subnormals as zero (same sign), as an x86 operand with MXCSR.DAZ set. Returns ``x``
    itself when no subnormal is present: the usual case, one test (a second one when zeros
    are present, which stay as they are)."""
    tiny = np.abs(x) < FLT_MIN
    if not tiny.any():
        return x
    tiny = np.logical_and(tiny, x, out=tiny if tiny.ndim else None)  # x as a truth value
    if not tiny.any():
        return x
    return np.where(tiny, np.copysign(F32(0.0), x), x)


_LOW29 = np.int64(
    0x1FFFFFFF
)  # NumPy scalars: a Python int operand costs a type resolution per call
_MID29 = np.int64(0x10000000)


def fma_sum(a: Any, b: Any, c: Any) -> np.ndarray:
    """float64 ``a*b + c`` of float32 operands (the product exact, the sum rounded once), in a
    new buffer. ``a.astype`` then in-place steps: half the cost of ``np.multiply(a, b,
    dtype=np.float64)`` on a few hundred lanes, the same bits."""
    b_shape = getattr(b, "shape", ())  # (np.shape/np.ndim cost microseconds on a scalar)
    if type(a) is np.ndarray and (b_shape == a.shape or not b_shape):
        s = a.astype(np.float64)
        np.multiply(s, b, out=s)
    else:
        s = np.multiply(a, b, dtype=np.float64)
    c_shape = getattr(c, "shape", ())
    if c_shape == s.shape or not c_shape or np.broadcast_shapes(c_shape, s.shape) == s.shape:
        np.add(s, c, out=s)
    else:
        s = np.add(s, c, dtype=np.float64)
    return s


def fma32(a: Any, b: Any, c: Any) -> np.ndarray:
    """float32 ``a*b + c`` with ONE rounding, like vfmadd. The float64 product of two float32
    values is exact; the float64 sum rounds once more, which can change the float32 result
    only when it lands exactly on a float32 midpoint (low 29 mantissa bits 1000...0) after an
    inexact addition. Those few elements get the exact error (TwoSum) and are moved one float64
    step towards it, so rounding to float32 is the correctly rounded fused result. (The sum is
    made in the product's buffer, which then holds the midpoint test; the operands of the rare
    midpoints are re-read and their float64 sum made again, the same bits.)"""
    s = fma_sum(a, b, c)
    r = s.astype(F32)
    low = np.bitwise_and(s.view(np.int64), _LOW29, out=s.view(np.int64))
    mid = low == _MID29
    if mid.any():
        at = np.nonzero(mid)
        ps = np.multiply(
            np.broadcast_to(a, r.shape)[at], np.broadcast_to(b, r.shape)[at], dtype=np.float64
        )
        cs = np.broadcast_to(c, r.shape)[at].astype(np.float64)
        ss = ps + cs
        bb = ss - ps
        err = (ps - (ss - bb)) + (cs - bb)  # TwoSum: ss + err == ps + cs exactly
        r[at] = np.where(err != 0, np.nextafter(ss, np.where(err > 0, np.inf, -np.inf)), ss)
    return r


_TWO31 = F32(2.0**31)


def cvtt(x: np.ndarray) -> np.ndarray:
    """x86 ``cvttps2dq`` of float32 ``x``: truncate to int32; NaN and out-of-range give INT_MIN.
    In range (|x| < 2**31; -2**31 itself gives INT_MIN either way) NumPy's cast truncates the
    same; only the other lanes are replaced (by -2**31) before it."""
    ok = np.abs(x) < _TWO31
    if not ok.all():
        x = np.where(ok, x, -_TWO31)
    return x.astype(I32)


def blocked(fn: Any, *args: np.ndarray) -> np.ndarray:
    """``fn(*args)`` (float32 in, float32 out, elementwise) evaluated on blocks of
    :data:`_BLOCK` lanes of the broadcast arguments: the two dozen temporaries of a built-in
    on a million lanes (8 MB each in float64) are then tile-sized and recycled by the allocator
    instead of being faulted in anew at every step (3-5x less CPU time at 1,000,000 lanes).
    Same bits as one call (every step is elementwise). 0-d arguments run as 1-lane arrays."""
    if len(args) == 1 and type(args[0]) is np.ndarray and args[0].ndim and args[0].size <= _BLOCK:
        return fn(args[0])  # the usual call: one lane array of a tile or less
    args = tuple(np.asarray(v) for v in args)
    shape = args[0].shape if len(args) == 1 else np.broadcast_shapes(*(v.shape for v in args))
    if not shape:
        return fn(*(v.reshape(1) for v in args)).reshape(())
    n = math.prod(shape)
    if n <= _BLOCK:
        return fn(*(v if v.ndim else v.reshape(1) for v in args))
    flat = [
        v.reshape(-1)
        if v.shape == shape
        else v.reshape(())
        if v.size == 1
        else np.broadcast_to(v, shape).reshape(-1)
        for v in args
    ]
    out = np.empty(n, F32)
    for i in range(0, n, _BLOCK):
        out[i : i + _BLOCK] = fn(*(v[i : i + _BLOCK] if v.ndim else v for v in flat))
    return out.reshape(shape)


def keeps_shape(r: np.ndarray, v: np.ndarray) -> bool:
    """Whether broadcasting ``v`` against ``r`` leaves ``r``'s shape (so ``r`` can take the
    result in place): the usual cases by their shapes, the rest by np.broadcast_shapes (which
    costs a few microseconds a call)."""
    rs, vs = r.shape, v.shape
    if rs == vs or (v.ndim <= r.ndim and (v.size == 1 or rs[r.ndim - v.ndim :] == vs)):
        return True
    return rs == np.broadcast_shapes(rs, vs)


class LlvmpipeMath:
    """gallivm's float32 sin/cos/exp2/log2/pow (lp_bld_arit.c, Mesa 22.3), with or without
    FMA. All inputs and results are float32 arrays. The public methods split large arrays
    into blocks (:func:`blocked`); the ``_``-prefixed ones are the algorithms, step by step."""

    # gallivm's coefficients (llvmpipe_math.coefficients): the exp2 and log2
    # polynomials, and the cosine's (y_6) and sine's (y2_6) polynomials of lp_build_sin_or_cos
    EXP2, LOG2, SIN_COS = coefficients.EXP2, coefficients.LOG2, coefficients.SIN_COS

    def __init__(self, fma: bool = HOST_FMA) -> None:
        self.fma = fma
        self._kernels: dict[str, Any] = {}

    def mad(self, a: Any, b: Any, c: Any, exact: bool = False) -> np.ndarray:
        """``llvm.fmuladd``: fused on an FMA CPU, else a*b then + c. ``exact``: the caller
        knows every float32 product a*b is exact, so fused and unfused agree."""
        if self.fma and not exact:
            return fma32(a, b, c)
        return np.add(np.multiply(a, b, dtype=F32), c, dtype=F32)

    def _fast(self, name: str) -> Any:
        """The algorithm ``name`` (``"_exp2"``, ...) with its fused multiply-adds checked for
        float32 midpoints once at the end instead of after each one (:class:`DeferredFma`):
        three NumPy calls fewer per fused step, which is most of the cost on the few hundred
        lanes a call has after compaction. When a float64 sum is a midpoint anywhere (rare), the
        call is made again on the reference path, which corrects each one: the same bits
        either way. Without FMA there is nothing to defer."""
        ref = getattr(self, name)
        if not self.fma:
            return ref

        def run(*args: np.ndarray) -> np.ndarray:
            if args[0].size > DEFER_LANES:
                return ref(*args)
            d = DeferredFma()
            r = getattr(d, name)(*args)
            return ref(*args) if d.midpoint() else r

        return run

    def _kernel(self, name: str) -> Any:
        """The algorithm ``name`` as llvmpipe_fast's kernel (the same steps in fewer NumPy
        calls, for arguments in the common range), else, where the kernel declines (edge
        arguments), :meth:`_fast`, which also recomputes the lanes of a float32 midpoint in
        the kernel: the same bits either way. Up to :data:`DEFER_LANES` lanes: on larger
        arrays (whole tiles) the kernel's float64 rows cost as much as the calls they save
        (measured alternately in one process: 1.5-1.8x faster at 143 lanes, 1.2-1.5x at
        3600, even at 16000-48000 for sin and exp2, pow slower there). Made once
        per name (a hot path: one call per tile, loop iteration and march step)."""
        run = self._kernels.get(name)
        if run is None:
            kernel, slow, fma = _FAST_KERNELS.get(name), self._fast(name), self.fma
            chosen = slow
            if kernel is not None:
                fast = kernel

                def with_kernel(*args: np.ndarray) -> np.ndarray:
                    if max(a.size for a in args) > DEFER_LANES:
                        return slow(*args)
                    r = fast(*args, fma, slow)  # slow: also for the lanes of a float32 midpoint
                    return slow(*args) if r is None else r

                chosen = with_kernel
            # compiled kernels (numba) where jit.py's rule says they pay; else run itself
            self._kernels[name] = run = jit.dispatch(name, chosen, fma)
        return run

    def builtin(self, name: str, ref: Any) -> Any:
        """Runtime's own float32 lowering ``ref`` of the built-in ``name`` (``"_atan"``,
        ``"_atan2"``, ``"_asin"``, ``"_acos"``: Mesa's, a dozen to forty NumPy operations a call)
        as jit.dispatch gives it: the compiled kernel where jit.py's rule says it pays, else
        ``ref``. Made once per name."""
        run = self._kernels.get(name)
        if run is None:
            self._kernels[name] = run = jit.dispatch(name, ref, self.fma)
        return run

    def polynomial(self, x: np.ndarray, coeffs: tuple[float, ...]) -> np.ndarray:
        """``lp_build_polynomial``: even and odd coefficients in x*x separately (each by
        Horner with mad), then ``mad(odd, x, even)``."""
        x2 = x * x
        even: np.ndarray | np.floating | None = None
        odd: np.ndarray | np.floating | None = None
        for i in range(len(coeffs) - 1, -1, -1):
            c = F32(coeffs[i])
            if i % 2 == 0:
                even = c if even is None else self.mad(x2, even, c)
            else:
                odd = c if odd is None else self.mad(x2, odd, c)
        return self.mad(odd, x, even)

    # ------------------------------------------------------------------ sin, cos
    def sin_or_cos(self, a: np.ndarray, cos: bool) -> np.ndarray:
        """``lp_build_sin_or_cos``: Cephes sinf/cosf as in sse_mathfun: j = (int(|x|*4/pi) + 1)
        & ~1, three-part Cody-Waite reduction by pi/4 (DP1..DP3), one of two polynomials, sign
        by integer bit tricks, clamped to [-1, 1] with minps/maxps (a NaN from an overflowed
        reduction becomes +1), and NaN for non-finite input. For |x| >= 2**31 * pi/4 the
        conversion gives INT_MIN, so the "reduced" argument is huge and the result is a
        clamped +-1 (cos(1e10) = 1, sin(1e10) = -1)."""
        return blocked(self._kernel("_cos" if cos else "_sin"), a)

    def tan(self, a: np.ndarray) -> np.ndarray:
        """``sin(x) / cos(x)`` (Mesa's GLSL tan), both from one reduction and one evaluation
        of each polynomial: the two share everything but the final selection and sign."""
        return blocked(self._kernel("_tan"), a)

    def _sin(self, a: np.ndarray) -> np.ndarray:
        return self._sin_cos_result(a, self._sin_cos_reduced(a), cos=False)

    def _cos(self, a: np.ndarray) -> np.ndarray:
        return self._sin_cos_result(a, self._sin_cos_reduced(a), cos=True)

    def _tan(self, a: np.ndarray) -> np.ndarray:
        reduced = self._sin_cos_reduced(a)
        return self._sin_cos_result(a, reduced, cos=False) / self._sin_cos_result(
            a, reduced, cos=True
        )

    def _sin_cos_reduced(self, a: np.ndarray) -> tuple[np.ndarray, ...]:
        """The part sin and cos share: |x| (DAZ), j = emm2_add & ~1, the reduced argument
        x_3 and both polynomials of it (y_10 the cosine one, y2_9 the sine one)."""
        ai = a.view(I32)
        x_abs = daz((ai & I32(0x7FFFFFFF)).view(F32))
        emm2_add = cvtt(x_abs * F32(coefficients.FOUR_OVER_PI))
        emm2_add += I32(1)  # wraps at INT_MAX, as paddd
        emm2_and = emm2_add & I32(~1)
        y_2 = emm2_and.astype(F32)
        # DP1 has 8 significant bits and DP2 11: times an integer j < 2**16 (resp. 2**13, so
        # |x| < ~51000, resp. ~6400) the float32 product is exact and the fused multiply-add
        # rounds like a multiply then an add (the cheap form). INT_MIN reads as 2**31 here.
        j_max = int(emm2_and.view(U32).max(initial=0))
        x_1 = self.mad(y_2, F32(coefficients.DP[0]), x_abs, exact=j_max < 2**16)
        x_2 = self.mad(y_2, F32(coefficients.DP[1]), x_1, exact=j_max < 2**13)
        x_3 = self.mad(y_2, F32(coefficients.DP[2]), x_2)
        z = x_3 * x_3
        # both polynomials have the form mad(mad(z, p0, p1), z, p2) * z: on few lanes evaluated
        # as one (2, lanes) array, row 0 the cosine's coefficients and row 1 the sine's
        # (elementwise, so the same bits as two calls, in half the NumPy calls); on a tile two
        # arrays of one row each are faster (measured: 1.2x the time with the stacked form)
        p = self.SIN_COS
        if z.size <= DEFER_LANES:  # (flat: the argument may be a vector, e.g. of shape (3, 1))
            zf = z.reshape(-1)
            stacked = self.mad(self.mad(zf, p[0], p[1]), zf, p[2])
            stacked *= zf
            both = [row.reshape(z.shape) for row in stacked]
        else:
            both = [
                self.mad(self.mad(z, p[0, i, 0], p[1, i, 0]), z, p[2, i, 0]) * z for i in (0, 1)
            ]
        y_10 = both[0]  # y_6 * z
        y_10 *= z
        y_10 -= z * F32(0.5)
        y_10 += F32(1.0)  # ((y_6*z)*z - z*0.5) + 1.0
        y2_9 = self.mad(both[1], x_3, x_3)  # y2_6 = both[1]
        return ai, emm2_add, emm2_and, y_10, y2_9

    @staticmethod
    def _sin_cos_result(a: np.ndarray, reduced: tuple[np.ndarray, ...], cos: bool) -> np.ndarray:
        """From :meth:`_sin_cos_reduced`: the sign (sin: the argument's sign flipped by bit 2
        of j; cos: bit 2 of j - 2, inverted), the polynomial picked by bit 1 of j (cos: of j - 2),
        the clamp and NaN for non-finite input. ``fmin(y, 1)``/``fmax(., -1)`` are minps/maxps
        here: a NaN y becomes 1 in both."""
        ai, emm2_add, emm2_and, y_10, y2_9 = reduced
        if cos:
            emm2_2 = emm2_and - I32(2)  # wraps, as psubd
            sign_bit = ((I32(4) & ~emm2_2).view(U32) << U32(29)).view(I32)
        else:
            emm2_2 = emm2_and
            sign_bit = (ai ^ (emm2_add.view(U32) << U32(29)).view(I32)) & I32(INT_MIN)
        # y = (emm2_2 & 2) == 0 ? y2_9 : y_10, as a bit select: np.where on a mask that
        # changes from lane to lane costs several times these four integer passes
        keep = ((emm2_2 & I32(2)) >> 1) - I32(1)  # all ones where bit 1 is clear
        yi = y2_9.view(I32) ^ y_10.view(I32)
        yi &= keep
        yi ^= y_10.view(I32)
        yi ^= sign_bit
        y = yi.view(F32)
        np.fmin(y, F32(1.0), out=y)  # lp_build_clamp
        np.fmax(y, F32(-1.0), out=y)
        finite = np.isfinite(a)
        if not finite.all():
            y[~finite] = F32(np.nan)
        return y

    # ------------------------------------------------------------------ exp2, log2, pow
    def exp2(self, x: np.ndarray) -> np.ndarray:
        """``lp_build_exp2``: clamp to [-126.99999, 128] (NaN passes), split floor/fraction,
        2**ipart from the exponent bits times a degree-5 polynomial of the fraction."""
        return blocked(self._kernel("_exp2"), x)

    def log2(self, x: np.ndarray) -> np.ndarray:
        """``lp_build_log2_safe``: exponent + y*P(y*y) with y = (m-1)/(m+1) for the mantissa m
        in [1, 2); then +Inf for +Inf, -Inf for 0 (subnormals too), NaN for x < 0. The edge
        masks are unordered compares, so NaN input hits all three and ends NaN."""
        return blocked(self._kernel("_log2"), x)

    def pow(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """``lp_build_pow``: exp2(log2_safe(x) * y), then 0 where x == 0 (an unordered compare:
        NaN x gives 0 too; so do subnormal x)."""
        return blocked(self._kernel("_pow"), x, y)

    def _exp2(self, x: np.ndarray) -> np.ndarray:
        # minps(128, x) then maxps(-126.99999, .): a NaN x passes both, as in np.minimum/maximum
        x = np.minimum(daz(x), F32(128.0))
        np.maximum(x, F32(-126.99999), out=x)
        ipart = np.floor(x)
        fpart = x - ipart
        # (ipart + 127) << 23 in uint32: the int32 wrap-around of paddd/pslld, bit for bit
        expipart = ((cvtt(ipart).view(U32) + U32(127)) << U32(23)).view(F32)
        return np.multiply(expipart, self.polynomial(fpart, self.EXP2), out=expipart)

    def _log2(self, x: np.ndarray) -> np.ndarray:
        i = x.view(I32)
        logexp = (((i & I32(0x7F800000)) >> 23) - I32(127)).astype(F32)
        mant = ((i & I32(0x007FFFFF)) | I32(0x3F800000)).view(F32)
        y = (mant - F32(1.0)) / (mant + F32(1.0))
        res = self.mad(y, self.polynomial(y * y, self.LOG2), logexp)
        if ((x >= FLT_MIN) & (x < F32(np.inf))).all():
            return res  # every x normal, positive and finite: no edge applies
        xd = daz(x)
        nan = np.isnan(x)
        res = np.where(
            (xd < F32(0.0)) | nan,
            F32(np.nan),
            np.where(xd == F32(0.0), F32(-np.inf), np.where(x == F32(np.inf), F32(np.inf), res)),
        )
        return res

    def _pow(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        zero = ~(np.abs(x) >= FLT_MIN)  # x == 0 after DAZ, or NaN
        if not zero.any():
            return self._exp2(self._log2(x) * y)
        # those lanes end 0 whatever log2 gives them (every step is elementwise): read as 0.5
        # there (log2 exactly -1), log2 keeps its path without edges when they were its only
        # edge (a clamped base, max(dot, 0.0), has zeros on most tiles), and exp2 gets no zero
        # from them (log2(1) would be one, which costs daz a second test)
        r = self._exp2(self._log2(np.where(zero, F32(0.5), x)) * y)
        np.copyto(r, F32(0.0), where=zero)
        return r


_FAST_KERNELS: dict[
    str, Callable[..., np.ndarray | None]
] = {  # LlvmpipeMath._kernel: name -> kernel(*args, fma, ref), None where it declines
    "_sin": lambda a, fma, ref: llvmpipe_fast.sin_cos(a, fma, False, ref),
    "_cos": lambda a, fma, ref: llvmpipe_fast.sin_cos(a, fma, True, ref),
    "_exp2": llvmpipe_fast.exp2,
    "_log2": llvmpipe_fast.log2,
    "_pow": llvmpipe_fast.pow,
}


class DeferredFma(LlvmpipeMath):
    """An FMA LlvmpipeMath for ONE call (a fresh instance per call: render threads share the
    runtime) whose fused multiply-adds round the float64 sum to float32 at once and keep the
    sum; :meth:`midpoint` then tells whether any sum is a float32 midpoint, the only case where
    that rounding differs from the fused one (see :func:`fma32`)."""

    def __init__(self) -> None:
        super().__init__(fma=True)
        self.sums: list[np.ndarray] = []

    def mad(self, a: Any, b: Any, c: Any, exact: bool = False) -> np.ndarray:
        if exact:
            return np.add(np.multiply(a, b, dtype=F32), c, dtype=F32)
        s = fma_sum(a, b, c)
        self.sums.append(s)
        return s.astype(F32)

    def midpoint(self) -> bool:
        """Whether any kept float64 sum has low 29 mantissa bits 1000...0 (the sums are
        this instance's own buffers, overwritten by the test)."""
        if not self.sums:
            return False
        flat = np.concatenate([s.reshape(-1) for s in self.sums])
        low = np.bitwise_and(flat.view(np.int64), _LOW29, out=flat.view(np.int64))
        return bool((low == _MID29).any())
