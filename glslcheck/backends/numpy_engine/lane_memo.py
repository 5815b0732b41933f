"""One computation per distinct uniform input: a memo in front of the llvmpipe math emulation.

A uniform value (the same in every lane, backends/cpu_core/uniformity.py) is an array of one lane,
so `sin(iTime * 0.5)` or a rotation `sin(float(i) * 0.7)` in a uniform loop costs one call per
tile, per loop iteration, per march step. For one lane the call is all overhead: the bit-exact
llvmpipe emulation (llvmpipe_reference.LlvmpipeMath: range reduction, polynomials, fused
multiply-adds) is 30-odd NumPy operations, about 0.1 ms, where the value was usually computed a
moment ago in another tile or iteration. `MemoMath` wraps the runtime's LlvmpipeMath and answers a
call whose arguments are all small (a scalar or vector of one lane) from a table keyed by their
exact bits, so each distinct input is computed once per render (and kept across frames until the
table is full). The answer is the emulation's own result, copied: bit for bit what the call
gives, llvmpipe's rounding included. Calls on lane arrays go straight through.
"""

from __future__ import annotations

from typing import Any

import numpy as np

SMALL = 16  # elements: a one-lane value up to a mat4 is answered from the table
LIMIT = 8192  # entries; the table starts afresh when full (animations bring new inputs each frame)


class MemoMath:
    """`MemoMath(lp)` behaves as the LlvmpipeMath `lp` (same methods, same results)."""

    def __init__(self, lp: Any) -> None:
        self._lp = lp
        self._table: dict[tuple, np.ndarray] = {}
        self.hits = self.misses = 0

    def __getattr__(self, name: str) -> Any:
        fn = getattr(self._lp, name)
        if not callable(fn) or name.startswith("_"):
            return fn

        def call(*args: Any, **kwargs: Any) -> Any:
            key = self._key(name, args, kwargs)
            if key is None:
                return fn(*args, **kwargs)
            out = self._table.get(key)
            if out is None:
                self.misses += 1
                out = fn(*args, **kwargs)
                if not isinstance(out, np.ndarray) or out.size > SMALL:
                    return out
                if len(self._table) >= LIMIT:
                    self._table = {}
                self._table[key] = out.copy()
                return out
            self.hits += 1
            return out.copy()  # a fresh array, as the call itself returns

        self.__dict__[name] = call  # made once per name: later calls skip __getattr__
        return call

    @staticmethod
    def _key(name: str, args: tuple, kwargs: dict) -> tuple | None:
        parts: list[Any] = [name, tuple(sorted(kwargs.items()))]
        for a in args:
            if isinstance(a, np.ndarray):
                if a.size > SMALL:
                    return None
                parts.append((a.dtype.str, a.shape, a.tobytes()))
            elif isinstance(a, (bool, int, float, np.generic)):
                parts.append((type(a).__name__, repr(a)))
            else:
                return None
        return tuple(parts)
