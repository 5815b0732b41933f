"""numba's typing of an operator (`a + b`, `a <= b`, `-a`) or an intrinsic (lanes_rt.lsel) once
per argument types per process, not once per use.

numba resolves each use of an operator afresh: type inference asks the operator's function type
for a signature (`BaseFunction.get_call_type`), which tries numba's templates for that operator
in turn (scalars, NumPy's ufunc loops, ...) with literal and plain arguments, and lowering asks
again for each binary operator. A lockstep module spells every per-pixel operation W times, all on
the same few types (float32, int32, uint32, bool), so most of those resolutions repeat one of a
handful. `replace()` remembers each successful resolution by (function type, typing context,
argument types, keywords, the compile's flags): the same signature object numba computed the
first time, and the template's implementation key it recorded then (numba's types are interned,
so an equal function type is the same object and keeps it). Failures are not remembered (numba
tries other routes and raises its own errors). Only operators, and functions whose templates
are all intrinsics' (`@intrinsic`: lsel, W times per per-pixel select; the template answers from
its own cache keyed by the context and the argument types, but first asks the target for its
registry of implementations, which refreshes the target's registries on every use): what their
templates answer depends on those alone.
"""

from __future__ import annotations

import operator
from typing import Any

from .numba_swaps import swap

CHECKED = ("0.68.",)  # the numba versions whose BaseFunction.get_call_type this wraps
OPERATORS = frozenset(
    v for k, v in vars(operator).items() if callable(v) and not k.startswith("_")
)  # (operator.add, operator.le, ...: the keys numba types Python's operators by)


def _memoized(numba_get_call_type: Any) -> Any:
    from numba.core import targetconfig
    from numba.core.typing.templates import _IntrinsicTemplate as _Intrinsic

    memo: dict = {}
    by_types: dict = {}  # function type -> whether its resolutions are remembered

    def remembered(self: Any) -> bool:
        known = by_types.get(self)
        if known is None:
            ts = getattr(self, "templates", ())
            intrinsics = bool(ts) and all(
                isinstance(t, type) and issubclass(t, _Intrinsic) for t in ts
            )
            known = by_types[self] = self.typing_key in OPERATORS or intrinsics
        return known

    def get_call_type(self: Any, context: Any, args: Any, kws: Any) -> Any:
        try:  # (an unhashable key or argument: numba's own resolution)
            # the compile's flags too: an operator numba implements by an @overload compiles
            # its implementation for them (numba's own cache of those is keyed so)
            flags = targetconfig.ConfigStack.top_or_none()
            key = (self, context, tuple(args), tuple(sorted(kws.items())), flags)
            mine = remembered(self)
            sig = memo.get(key) if mine else None
            hit = sig is not None and sig.args in self._impl_keys
        except TypeError:
            key, mine, hit = None, False, False
        if hit:
            return sig
        sig = numba_get_call_type(self, context, args, kws)
        if sig is not None and key is not None and mine:
            memo[key] = sig
        return sig

    return get_call_type


def replace() -> bool:
    """Put the memoized resolution in the place of numba's (numba_patches.install: once, on
    the `CHECKED` versions); False when this numba lacks what it wraps."""
    from numba.core.types import functions

    base = getattr(functions, "BaseFunction", None)
    if base is None:
        return False
    if not hasattr(base, "get_call_type") or not hasattr(base, "get_impl_key"):
        return False
    swap(base, "get_call_type", _memoized(base.get_call_type))
    return True
