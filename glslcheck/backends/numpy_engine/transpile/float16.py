"""Arithmetic on lowp lookups in float16 (cpu_core/nir_fold/lower_precision.py), written by the
NumPy transpiler: the float16 tree as NumPy float16 operations, taken where the samplers are
lowp."""

from __future__ import annotations

from typing import Any

from ....frontend import syntax as A
from ...cpu_core.nir_fold.lower_precision import float16_code, float16_tree

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable

    from .state import TranspilerState


def lowp_tree(tr: TranspilerState, e: A.Binary, mask: str | None) -> str | None:
    """``e`` computed in float16 where llvmpipe does, else None.

    Mesa's GLSL compiler lowers GLSL ES precision to float16 (glsl/lower_precision.cpp, on
    for llvmpipe): an operation whose operands are all lowp or mediump runs in float16, a
    constant taking its partner's precision (rounded to float16 to nearest), and the result
    is converted to float32 where a highp operand or variable takes it. Shadertoy's iChannels
    are lowp sampler2D (backends/numpy_engine/textures.py), so ``2.1 + 0.1*textureLod(iChannel2, uv,
    0.0).x`` (elephant's terrain height) is two float16 operations on llvmpipe: 2.130859375
    where float32 gives 2.1319335. Copied for trees of ``+ - * /`` and negation whose leaves
    are literal constants (a `const` variable or a never-written global is a highp variable
    here, measured) and lookups on an iChannel (swizzled or not), at least one lookup; measured
    bit for bit (tests/gl/test_llvmpipe_lowering.py). Emitted as ``(rt.lowp_full(<float16
    tree>) if rt.lowp_arith(<samplers>) else <written>)``: float64 and float16 renders, and
    samplers that are not lowp (the WebGL comparison's), keep float32. ``pow(x, 2.0)`` is
    ``x * x`` there (measured). Not copied: other built-in calls on such
    values (``smoothstep(0.3, 0.4, texture(..).x)`` is float16 on llvmpipe too,
    not measured), lookups through a sampler parameter, mediump/lowp variables (see
    glslcheck/semantics/mediump.py), and NIR's reassociations inside the float16 tree."""
    if (
        tr.fn is None
        or tr.fold_state.lowp_written is not None
        and id(e) in tr.fold_state.lowp_written
    ):
        return None
    tree = float16_tree(tr, e)
    if tree is None:
        return None
    ops, samplers = tree
    low = float16_code(tr.model, e, ops, _NumpyFloat16(tr, mask))
    tr.fold_state.lowp_written = ops  # the written form: this tree without the rule
    try:
        written = tr.expr(e, mask)
    finally:
        tr.fold_state.lowp_written = None
    used = ", ".join(dict.fromkeys(tr.expr(s, mask) for s in samplers))
    return f"(rt.lowp_full({low}) if rt.lowp_arith({used}) else {written})"


class _NumpyFloat16:
    """The NumPy backend's float16 tree: leaves rounded by ``rt.half``, each operation a NumPy
    float16 operation (one rounding each), a value read twice named by ``:=``."""

    def __init__(self, tr: TranspilerState, mask: str | None) -> None:
        self.tr, self.mask = tr, mask

    def leaf(self, node: Any) -> str:
        return f"rt.half({self.tr.expr(node, self.mask)})"

    def negate(self, x: str) -> str:
        return f"(-{x})"

    def op(self, op: str, a: str, b: str) -> str:
        return f"({a} {op} {b})"

    def shared(self, build: Callable[[], str]) -> tuple[str, str]:
        h = self.tr.fresh("h")
        return f"({h} := {build()})", h
