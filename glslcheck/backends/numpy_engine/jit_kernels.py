"""The llvmpipe math emulation as compiled loops (numba): one pass over the lanes per call.

llvmpipe_reference.LlvmpipeMath makes gallivm's sin/cos/exp2/log2/pow (lp_bld_arit.c) as 30-70 NumPy
operations; on the few hundred lanes of a compacted march loop each costs more than its
arithmetic. These kernels make the same float32 operations, in the same order with the same
roundings, lane by lane in one compiled loop without a branch out of it, which LLVM
vectorises (10-40x less CPU a call at 143 lanes, 6-9x on a whole tile: docs/performance.md,
"The llvmpipe math emulation").

The one-lane algorithms are backends/llvmpipe_math/lane.py's (which the compiled engine calls per
pixel too); this module runs them over arrays. Imported only by backends/numpy_engine/jit.py, which
decides when loading them pays (importing numba and loading the machine code from numba's cache
take seconds); this module points numba's cache directory first.

- A fused multiply-add (``llvm.fmuladd``, fused on an FMA CPU) is LLVM's own ``llvm.fma.f32``
  (lane.mad): one rounding, as vfmadd, which llvmpipe_reference.fma32 emulates in float64;
  without FMA it is a float32 multiply then add, as llvmpipe does there.
- DAZ: a subnormal operand of these algorithms reads as a zero of its sign, as in
  LlvmpipeMath (llvmpipe_reference.daz).
- Each kernel first scans its arguments and returns False, writing nothing useful, where some
  lane would give a NaN (the bits of a NaN LLVM makes here need not be the ones NumPy's
  reference writes) or leave the range where the reference's integer conversions cannot
  overflow (sin/cos/tan: |x| >= 2**29); the caller then takes the NumPy path. Every other
  edge (+-0, subnormals, +-Inf where the result is finite or an infinity) is computed here.

:func:`arc` makes the Runtime's own lowerings of atan, atan(y, x), asin and acos (Mesa's, no
fused step) the same way.

Bit for bit against LlvmpipeMath's and the Runtime's reference, both FMA modes:
tests/numpy/test_jit_kernels.py; against llvmpipe itself: tests/gl/test_jit_llvmpipe.py.
"""

from __future__ import annotations

from ..cpu_core.numba_cache import use_cache_dir

use_cache_dir()  # numba's cache directory first

import numba  # noqa: E402
import numpy as np  # noqa: E402

from ..llvmpipe_math import lane  # noqa: E402

F32 = np.float32
_OPTS = lane.OPTIONS
_ONE, _ZERO = lane.ONE, lane.ZERO


@numba.njit("boolean(float32[::1], float32[::1], boolean, int64)", **_OPTS)
def trig(a, out, fma, which):
    """llvmpipe_math.lane.trig of every lane of ``a`` into ``out`` (same size); False (declined)
    where some
    |x| >= 2**29 or is not finite."""
    n = a.size
    for k in range(n):
        if not lane.trig_in_range(a[k]):
            return False
    for k in range(n):
        out[k] = lane.trig(a[k], fma, which)
    return True


@numba.njit("boolean(float32[::1], float32[::1], float32[::1], boolean, int64)", **_OPTS)
def explog(x, y, out, fma, which):
    """LlvmpipeMath._exp2 (``which`` 0), _log2 (1) of ``x``, or _pow (2) of ``x`` and ``y``, into
    ``out``; x and y have out's size or one element (broadcast). False (declined) where some
    lane's result would be a NaN: exp2 of NaN, log2 of a negative number or NaN, pow where
    log2(x) * y is NaN (x < 0; 0 * Inf)."""
    n = out.size
    nx = x.size
    ny = y.size
    for k in range(nx):
        b = np.int64(lane.bits(x[k]))
        if (b & lane.ABS_BITS) > lane.INF_BITS:
            if which != 2:
                return False  # NaN (pow: x NaN gives 0, below)
        elif which != 0 and b >= 0x80000000 and (b & lane.ABS_BITS) >= lane.MIN_NORMAL_BITS:
            return False  # a negative number: log2 is NaN
    if which == 0:
        for k in range(n):
            out[k] = lane.exp2(x[k], fma)
    elif which == 1:
        for k in range(n):
            out[k] = lane.log2(x[k], fma)
    # no exit from this loop, so that LLVM can vectorise it: a NaN is noted and told at the end
    else:
        nan = False
        for k in range(n):
            xk = x[k if nx > 1 else 0]
            # x == 0 after DAZ, or NaN
            zero = (np.int64(lane.bits(xk)) & lane.ABS_BITS) < lane.MIN_NORMAL_BITS or xk != xk
            t = F32(lane.log2(_ONE if zero else xk, fma) * y[k if ny > 1 else 0])
            nan |= t != t and not zero
            r = lane.exp2(_ZERO if t != t else t, fma)
            out[k] = _ZERO if zero else r
        return not nan
    return True


@numba.njit("boolean(float32[::1], float32[::1], float32[::1], boolean, int64)", **_OPTS)
def arc(x, y, out, fma, which):
    """Runtime.atan (``which`` 0), asin (1), acos (2) of ``x``, or atan (3) of ``x`` over ``y``
    (GLSL's atan(y, x) with its y first), into ``out``; x and y have out's size or one element,
    as for :func:`explog`. ``fma`` is unused (the same signature as explog: none of these has a
    fused step). False (declined) for asin or acos where some |x| > 1 or x is NaN (the result
    would be a NaN); atan and atan2 never give one."""
    n = out.size
    nx = x.size
    ny = y.size
    if which == 1 or which == 2:
        for k in range(nx):
            if not abs(x[k]) <= _ONE:
                return False
    for k in range(n):
        out[k] = lane.arc(x[k if nx > 1 else 0], y[k if ny > 1 else 0], which)
    return True


# ---------------------------------------------------------------- mix
@numba.njit("boolean(float32[:, ::1], float32[:, ::1], float32[:, ::1], float32[:, ::1])", **_OPTS)
def mix(x, y, a, out):
    """Runtime.mix's "fast" form (nir_lower_flrp's ``x + a*(y - x)`` in every lane) into
    ``out``, of shape (components, lanes); x, y and a have out's number of rows or one, and its
    number of columns or one (broadcast, as a vec3 constant of shape (3, 1) or a float weight
    against vec3 lanes: nothing is copied to broadcast). False (declined) where a lane gives a
    NaN (its bits are NumPy's to choose)."""
    rows, cols = out.shape
    nan = False
    for i in range(rows):
        xi = i if x.shape[0] > 1 else 0
        yi = i if y.shape[0] > 1 else 0
        ai = i if a.shape[0] > 1 else 0
        for k in range(cols):
            xk = x[xi, k if x.shape[1] > 1 else 0]
            yk = y[yi, k if y.shape[1] > 1 else 0]
            ak = a[ai, k if a.shape[1] > 1 else 0]
            t = F32(xk + F32(ak * F32(yk - xk)))
            nan |= t != t
            out[i, k] = t
    return not nan
