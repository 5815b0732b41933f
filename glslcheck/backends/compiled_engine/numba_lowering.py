"""numba's ABI size of an LLVM type once per type per process, not once per variable.

When numba lowers a function it gives each of its named variables a stack slot, and for each
it asks the size of the slot's LLVM type (`BaseContext.get_abi_sizeof`, for debug information
it then does not emit unless asked): llvmlite answers by writing a module that declares a
global of that type and having LLVM parse it. A lockstep module names W variables for every
per-pixel one, all of a few types (float, i1, i32, an array's struct), so the parses repeat a
handful of answers thousands of times. `replace()` remembers each answer by the type's IR text
and the target's data layout: a literal type's size is a function of those alone (identified
structs, named and defined elsewhere, are not remembered).
"""

from __future__ import annotations

from typing import Any

from .numba_swaps import swap

CHECKED = ("0.68.",)  # the numba versions whose BaseContext.get_abi_sizeof this wraps


def _memoized(numba_get_abi_sizeof: Any) -> Any:
    from llvmlite import ir

    memo: dict = {}

    def get_abi_sizeof(self: Any, ty: Any) -> int:
        if not isinstance(ty, ir.Type) or _identified(ty):
            return numba_get_abi_sizeof(self, ty)
        key = (str(ty), str(self.target_data))
        size = memo.get(key)
        if size is None:
            size = memo[key] = numba_get_abi_sizeof(self, ty)
        return size

    return get_abi_sizeof


def _identified(ty: Any) -> bool:
    """Whether ty is or holds a struct known by its name (its layout is not in its text)."""
    from llvmlite import ir

    seen = [ty]
    while seen:
        t = seen.pop()
        if isinstance(t, ir.IdentifiedStructType):
            return True
        if isinstance(t, ir.BaseStructType):
            seen += list(t.elements)
        elif isinstance(t, (ir.ArrayType, ir.VectorType)):
            seen.append(t.element)
    return False


def replace() -> bool:
    """Put the memoized size in the place of numba's (numba_patches.install: once, on the
    `CHECKED` versions); False when this numba lacks what it wraps."""
    from numba.core import base

    context = getattr(base, "BaseContext", None)
    if context is None or not hasattr(context, "get_abi_sizeof"):
        return False
    swap(context, "get_abi_sizeof", _memoized(context.get_abi_sizeof))
    return True
