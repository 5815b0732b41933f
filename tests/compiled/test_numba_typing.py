"""numba_typing's memoized operator typing against numba's own resolution: the same signature
and implementation for every operator and argument types the generated modules use, on the first
use and on the remembered ones, and numba's own error where numba has no signature."""

from __future__ import annotations

import operator

import pytest

from glslcheck.backends.compiled_engine import numba_swaps

BINARY = [
    operator.add,
    operator.sub,
    operator.mul,
    operator.truediv,
    operator.mod,
    operator.lt,
    operator.le,
    operator.eq,
    operator.ne,
    operator.gt,
    operator.ge,
    operator.and_,
    operator.or_,
    operator.xor,
    operator.lshift,
    operator.rshift,
]
UNARY = [operator.neg, operator.not_, operator.invert, operator.pos]


def _types():
    from numba.core import types

    return [
        types.float32,
        types.float64,
        types.int32,
        types.int64,
        types.uint32,
        types.boolean,
        types.IntegerLiteral(3),
        types.BooleanLiteral(True),
    ]


def _resolve(get_call_type, fnty, ctx, args):
    """(signature, implementation key) or the error's type when numba has none."""
    try:
        sig = get_call_type(fnty, ctx, args, {})
    except Exception as e:  # noqa: BLE001 (the comparison is of numba's errors)
        return type(e)
    return (sig, fnty.get_impl_key(sig)) if sig is not None else None


@pytest.fixture
def typing(numba):
    """(numba's CPU typing context, refreshed; numba's own get_call_type), numba_typing
    installed in its place (skipped on a numba other than the one it was checked on). lanes_rt
    is imported first: the refresh registers its intrinsics."""
    from numba.core import registry
    from numba.core.types.functions import BaseFunction

    from glslcheck.backends.compiled_engine import (
        lanes_rt,  # noqa: F401
        numba_patches,
        numba_typing,
    )

    if not numba_patches.install(numba_typing):
        pytest.skip(f"numba_typing is not installed on numba other than {numba_typing.CHECKED}")
    ctx = registry.cpu_target.typing_context
    ctx.refresh()
    return ctx, numba_swaps.original(BaseFunction, "get_call_type")


def _same_resolutions(ctx, own, cases) -> int:
    """Each (function, argument types) of `cases` resolved by the installed get_call_type, on the
    first use and on the remembered one, as numba's own resolves it: how many have a signature."""
    from numba.core.types.functions import BaseFunction

    resolved = 0
    for fn, args in cases:
        fnty = ctx.resolve_value_type(fn)
        want = _resolve(own, fnty, ctx, args)
        for _ in range(2):  # the first use, then the remembered one
            got = _resolve(BaseFunction.get_call_type, fnty, ctx, args)
            assert got == want, (fn, args)
        resolved += isinstance(want, tuple)
    return resolved


def _memoized_counting(own, calls: list):
    """numba_typing's memo around numba's own get_call_type, each call it lets through appended
    to `calls`."""
    from glslcheck.backends.compiled_engine import numba_typing

    def counting(self, context, args, kws):
        calls.append(args)
        return own(self, context, args, kws)

    return numba_typing._memoized(counting)


def test_operators_same_signatures_as_numba(typing):
    ctx, own = typing
    ts = _types()
    cases = [(op, (a, b)) for op in BINARY for a in ts for b in ts]
    cases += [(op, (a,)) for op in UNARY for a in ts]
    resolved = _same_resolutions(ctx, own, cases)
    assert resolved > len(cases) // 2  # (most combinations have a signature)


def test_other_functions_are_numba_s(typing):
    """A function type that is not an operator's is resolved by numba each time."""
    from numba.core import types
    from numba.core.types.functions import BaseFunction

    ctx, own = typing
    fnty = ctx.resolve_value_type(abs)
    calls = []
    wrapped = _memoized_counting(own, calls)
    for _ in range(2):
        assert wrapped(fnty, ctx, (types.float32,), {}) == own(fnty, ctx, (types.float32,), {})
    assert len(calls) == 2
    le = ctx.resolve_value_type(operator.le)
    for _ in range(3):
        wrapped(le, ctx, (types.float32, types.float32), {})
    assert len(calls) == 3  # (the operator resolved once)
    assert BaseFunction.get_call_type is not own


def test_intrinsics_same_signatures_as_numba(typing):
    """An intrinsic's typing (lanes_rt.lsel, lzero) is numba's, resolved once per argument types;
    an argument type it refuses is numba's error each time."""
    from numba.core import types

    from glslcheck.backends.compiled_engine import lanes_rt

    ctx, own = typing
    ts = _types()
    cases = [(lanes_rt.lsel, (c, a, b)) for c in ts for a in ts for b in ts]
    cases += [(lanes_rt.lzero, (a,)) for a in ts]
    resolved = _same_resolutions(ctx, own, cases)
    assert 0 < resolved < len(cases)  # (lsel refuses a condition that is not a bool)
    calls = []
    wrapped = _memoized_counting(own, calls)
    fnty = ctx.resolve_value_type(lanes_rt.lsel)
    args = (types.boolean, types.float32, types.float32)
    for _ in range(3):
        assert wrapped(fnty, ctx, args, {}) == own(fnty, ctx, args, {})
    assert len(calls) == 1
