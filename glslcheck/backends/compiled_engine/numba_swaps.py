"""numba's own functions that the patches (numba_patches) put glslcheck's code in the place of:
:func:`swap` replaces one and keeps numba's, :func:`original` gives it back (the reference each
patch's tests compare with). Below every patch, which imports it; it imports none of them."""

from __future__ import annotations

from typing import Any

# (id(owner), name) -> (owner, kept alive; numba's own owner.name before the first swap)
_ORIGINALS: dict[tuple[int, str], tuple[Any, Any]] = {}


def swap(owner: Any, name: str, wrapper: Any) -> None:
    """Put wrapper in the place of owner.name (a module's function, a class's method), keeping
    what was there for :func:`original`: only the first time, so a later swap of the same
    attribute still leaves numba's own as the original."""
    _ORIGINALS.setdefault((id(owner), name), (owner, getattr(owner, name)))
    setattr(owner, name, wrapper)


def original(owner: Any, name: str) -> Any:
    """numba's own owner.name: what the first swap of it replaced, else the attribute itself."""
    kept = _ORIGINALS.get((id(owner), name))
    return kept[1] if kept is not None else getattr(owner, name)
