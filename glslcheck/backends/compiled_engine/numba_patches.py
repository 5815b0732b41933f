"""Where glslcheck's code takes the place of parts of numba's compiler, and installing it once
per process: numba_ssa (SSA reconstruction, phi removal), numba_typing (operator typing),
numba_analysis (liveness, scope fix-up), numba_lowering (ABI sizes) and numba_linking (no
machine code for a generated module's callees). Each such module names the numba versions whose
internals it was checked against (`CHECKED`) and puts itself in place (`replace()`: False when
this numba lacks what it replaces) by numba_swaps.swap, which keeps numba's own for
numba_swaps.original (the reference each one's tests compare with); :func:`install` runs that
once, on those versions only, and numba's own code runs everywhere else."""

from __future__ import annotations

import threading
from typing import Protocol


class Patch(Protocol):
    """A module that takes the place of part of numba (the module doc)."""

    @property
    def CHECKED(self) -> tuple[str, ...]: ...  # the numba versions (prefixes) it was checked on

    def replace(self) -> bool: ...


_LOCK = threading.Lock()
_INSTALLED: dict[int, tuple[Patch, bool]] = {}  # id(patch) -> (it, kept alive; whether in place)


def install(patch: Patch) -> bool:
    """Put `patch` in the place of numba's own code (once per process); False when this numba is
    not one it was checked against (numba's own then runs)."""
    from numba import __version__

    with _LOCK:
        if id(patch) not in _INSTALLED:
            ok = __version__.startswith(patch.CHECKED) and patch.replace()
            _INSTALLED[id(patch)] = (patch, ok)
        return _INSTALLED[id(patch)][1]


def install_all() -> None:
    """Every patch (before numba compiles a module cold: what each saves is compile time)."""
    from . import numba_analysis, numba_linking, numba_lowering, numba_ssa, numba_typing

    for patch in (numba_ssa, numba_typing, numba_analysis, numba_lowering, numba_linking):
        install(patch)
