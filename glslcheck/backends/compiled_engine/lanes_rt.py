"""The lockstep modules' own runtime (lanes.py): a branch-free select, and the derivative of a
value the same in every lane.

`lsel(c, a, b)` is `a if c else b` as LLVM's `select` instruction. Written as Python's
conditional expression, each of the lanes' masked writes would be two basic blocks in numba's
IR: a function of a few thousand of them takes numba's SSA pass past Python's recursion limit
(16 lanes) and its compile time grows with them; as one instruction it is neither, and LLVM's
SLP vectorizer can make W of them one blend.
"""

from __future__ import annotations

from numba.core import types
from numba.core.imputils import impl_ret_borrowed
from numba.extending import intrinsic


@intrinsic
def lsel(typingctx, c, a, b):
    """a where the bool c holds, else b (both computed; their unified type: a literal True and
    a bool are a bool)."""
    if not isinstance(c, types.Boolean):
        return None
    t = a if a == b else typingctx.unify_types(a, b)
    if t is None:
        return None
    t = types.unliteral(t)

    def codegen(context, builder, signature, args):
        sa, sb = signature.args[1], signature.args[2]
        x = context.cast(builder, args[1], sa, t)
        y = context.cast(builder, args[2], sb, t)
        c_ = context.cast(builder, args[0], signature.args[0], types.boolean)
        value = builder.select(c_, x, y)
        return impl_ret_borrowed(context, builder, t, value)  # arrays: one more reference

    return t(c, a, b), codegen


@intrinsic
def dfdx(typingctx, v):
    """dFdx of a value that is the same in every lane of the block (the rewrite writes a
    varying one as the difference of two lanes, lanes_render.quad_lanes): 0, as the NumPy backend's
    derivative of a lane-uniform value (runtime.Runtime._quad_diff)."""
    t = types.unliteral(v)
    if not isinstance(t, types.Float):
        return None

    def codegen(context, builder, signature, args):
        return context.get_constant(t, 0.0)

    return t(v), codegen


dfdy = qdx = qdy = dfdx  # the same 0 for a uniform value (qdx, qdy: lanes_render.quad_lanes)


@intrinsic
def lzero(typingctx, v):
    """The zero (False) of v's type: what a function's return value holds, before any return
    wrote it, in the lanes its mask leaves out (the NumPy backend's `_rv`, llvmpipe's). An
    array (numba's) is v itself: its slot keeps the first value written."""
    t = types.unliteral(v)
    if isinstance(t, types.Array):

        def same(context, builder, signature, args):
            return impl_ret_borrowed(context, builder, t, args[0])

        return t(v), same
    if not isinstance(t, (types.Float, types.Integer, types.Boolean)):
        return None

    def codegen(context, builder, signature, args):
        return context.get_constant(t, False if isinstance(t, types.Boolean) else 0)

    return t(v), codegen
