"""The host C library's float32 sin and cos, as Mesa's constant folding computes fsin and fcos
(nir_constant_expressions calls sinf and cosf): what llvmpipe's compile-time value of a
built-in of constants is, where it differs from gallivm's run-time function
(cpu_core/fold_eval.py's tan; measured: tests/gl/test_llvmpipe_constant_components.py)."""

from __future__ import annotations

from typing import Any

import numpy as np

_LIBM: list[Any] = []  # the host C library's (sinf, cosf), or None: loaded once when needed


def host_sin_cos(v: float) -> tuple[float, float] | None:
    """(sinf(v), cosf(v)) of the host C library in float32; None where no C math library is
    found (the caller keeps the run-time function)."""
    if not _LIBM:
        import ctypes
        import ctypes.util

        found = ctypes.util.find_library("m")
        fns = None
        if found:
            libm = ctypes.CDLL(found)
            fns = (libm.sinf, libm.cosf)
            for f in fns:
                f.restype, f.argtypes = ctypes.c_float, [ctypes.c_float]
        _LIBM.append(fns)
    if _LIBM[0] is None:
        return None
    sinf, cosf = _LIBM[0]
    return float(np.float32(sinf(v))), float(np.float32(cosf(v)))
