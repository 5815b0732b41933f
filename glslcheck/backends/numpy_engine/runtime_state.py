"""The base of every part of the NumPy runtime: what the parts share, declared for type checkers.

`Runtime` (runtime.py) is made of one class per concern (values, arithmetic, transcendental
and common functions, textures); each part reads the state `Runtime.__init__` sets up (the
float type and its constants, llvmpipe's math) and calls methods another part defines.
`RuntimeState` declares both, so each part is checked on its own against them (and mypy checks
each definition against its declaration). At run time it is an empty class.
"""

from __future__ import annotations

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

    import numpy as np

    from .lane_memo import MemoMath
    from .llvmpipe_reference import LlvmpipeMath


class RuntimeState:
    if TYPE_CHECKING:
        # Set up by Runtime.__init__ (see there).
        F: type[np.floating]
        precision: str
        float_to_uint: str
        lp: LlvmpipeMath | MemoMath | None  # (MemoMath: a transpiled program's, lane_memo.py)
        fold_constants: bool
        _dtype: np.dtype
        _0: np.floating
        _1: np.floating
        _2: np.floating
        _3: np.floating
        _half: np.floating
        _last_weight: tuple

        # ValueOps (runtime_values.py)
        def _f(self, x: Any) -> np.ndarray: ...
        def _pair(self, a: Any, b: Any) -> tuple[np.ndarray, np.ndarray]: ...
        def _num(self, x: Any) -> np.ndarray: ...
        @staticmethod
        def _stack(comps: list[np.ndarray]) -> np.ndarray: ...

        # ArithmeticOps (runtime_operators.py)
        def sub(self, a: Any, b: Any) -> np.ndarray: ...
        def fmul(self, a: np.ndarray, b: np.ndarray) -> np.ndarray: ...
        @staticmethod
        def _const(z: np.ndarray) -> bool: ...
        def lt(self, a: Any, b: Any) -> np.ndarray: ...
        def le(self, a: Any, b: Any) -> np.ndarray: ...
        def gt(self, a: Any, b: Any) -> np.ndarray: ...
        def ge(self, a: Any, b: Any) -> np.ndarray: ...
        def eq(self, a: Any, b: Any) -> np.ndarray: ...
        def ne(self, a: Any, b: Any) -> np.ndarray: ...
        def dot(self, a: Any, b: Any) -> np.ndarray: ...

        # CommonFunctions (runtime_common.py)
        def sign(self, x: Any) -> np.ndarray: ...
        def clamp(self, x: Any, lo: Any, hi: Any) -> np.ndarray: ...
