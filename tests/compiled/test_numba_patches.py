"""numba_patches: each replacement of part of numba is put in place once per process, and only
on the numba versions it was checked against."""

from __future__ import annotations

from types import SimpleNamespace

from glslcheck.backends.compiled_engine import numba_swaps


def _patch(checked: tuple[str, ...], calls: list[str], name: str) -> SimpleNamespace:
    def replace() -> bool:
        calls.append(name)
        return True

    return SimpleNamespace(CHECKED=checked, replace=replace)


def test_a_patch_replaces_once_and_only_on_a_checked_version(numba):
    from numba import __version__

    from glslcheck.backends.compiled_engine import numba_patches

    calls: list[str] = []
    here = _patch((__version__,), calls, "here")
    other = _patch(("0.0.",), calls, "other")
    assert [numba_patches.install(here) for _ in range(3)] == [True] * 3
    assert [numba_patches.install(other) for _ in range(2)] == [False] * 2
    assert calls == ["here"]  # replaced once; never on a version it was not checked on


def test_the_engine_patches_are_in_place_exactly_on_their_checked_versions(numba):
    """install_all puts each of the five in place where numba's version is one it names."""
    from numba import __version__

    from glslcheck.backends.compiled_engine import (
        numba_analysis,
        numba_linking,
        numba_lowering,
        numba_patches,
        numba_ssa,
        numba_typing,
    )

    numba_patches.install_all()
    patches = (numba_ssa, numba_typing, numba_analysis, numba_lowering, numba_linking)
    assert [numba_patches.install(p) for p in patches] == [
        __version__.startswith(p.CHECKED) for p in patches
    ]


def test_swap_keeps_the_first_original():
    """swap puts the wrapper in place; original gives what the first swap replaced, through a
    second swap of the same attribute, and the attribute itself where nothing was swapped."""

    def own() -> str:
        return "own"

    def first() -> str:
        return "first"

    def second() -> str:
        return "second"

    owner, other = SimpleNamespace(f=own), SimpleNamespace(f=own)
    assert numba_swaps.original(owner, "f") is own
    numba_swaps.swap(owner, "f", first)
    assert owner.f is first and numba_swaps.original(owner, "f") is own
    numba_swaps.swap(owner, "f", second)
    assert owner.f is second and numba_swaps.original(owner, "f") is own
    assert other.f is own and numba_swaps.original(other, "f") is own
