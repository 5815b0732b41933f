"""Mesa's NIR rewrites that change float32 bits, emitted by the transpiler for llvmpipe mode.

Mesa 22.3's compiler reassociates float arithmetic that GLSL ES 3.00 leaves unordered (no
`precise`): nir_opt_algebraic's inexact (`~`) rules rewrite the written expression, so llvmpipe
computes other float32 roundings than the source spells. A hash (`fract(x * 43758.5453)`)
amplifies the last bit, so verify mismatches unless the NumPy backend rewrites the same way.
The rules copied here, each measured bit for bit against llvmpipe on 50,000 random operands
(tests/gl/test_llvmpipe_lowering.py), one family per module:

- factoring.py: ``a*b + a*c -> a * (b + c)``, also through never-written locals and values
  ssa_values keeps, and again with a third term (``k*x + k*y + k*z`` is ``k * ((x + y) + z)``);
- sink.py: constants sunk into a sum or a product used once, ``(a + b) + #c -> (a + #c) + b``;
- squared_lengths.py: ``pow(length(x), 2.0) + #c`` is ``dot(x, x) + #c``, the constant inside;
- constant_merge.py: ``#a * (b * #c) -> (a*c) * b`` and ``#a + (b + #c) -> (a + c) + b``;
- constant_components.py: those merges, and the sink, where a vector constructor's constant
  component takes part (``7.0 * normalize(vec3(x, y, -6.0))`` is ``-42.0 * rsq`` in z);
- dot_constants.py: constants merged into a ``dot`` with a constant, ``dot(vecN(s), #K)`` factored;
- exp_log.py: ``exp`` and ``log`` as Mesa's products, ``exp(x * #k)`` is ``exp2(x * (k*log2(e)))``;
- ffma_split.py: ``(p1 + p2) + e`` returned through a folded call is ``(p1 + e) + p2`` (ffma);
- product_sums.py: ``(p1 + p2) + e`` is ``(p1 + e) + p2`` where p1 and p2 are products and e
  is none (a path tracer's ``p.x*c1 + p.y*c2 + iTime``);
- returned_sums.py: a constant added to a call's result sinks into the ``+=`` chain it returns;
- repeated_sums.py: ``seed += 0.1`` written again and again is ``seed0 + K``, also through calls
  NIR inlines and loops it unrolls; sum_order.py: K in the order Mesa's passes merge it;
- ssa_values.py: a variable assigned again still stands for its value (``p = m*p*2.02``);
- components.py: NIR's SSA per vector component, constants merged through component writes,
  a ``+= e`` undone by a later ``-= e``;
- compound_products.py: ``x *= b; ... x * #c`` with the new x read once is ``(a * #c) * b``;
- loop_copies.py: constants merged into the value a variable holds in each copy of a loop NIR
  unrolls (the value before the loop in the first), and into a sum through a variable assigned
  again; loop_compounds.py: the same for ``x *= #k`` (``+=``, ``-=``);
- loop_unroll.py: which loops NIR unrolls (a constant count, a body small enough);
- return_register.py: a call's result in the lanes a mask leaves out, llvmpipe's register;
- inlined_results.py: a call of a function that, inlined, is a value of its arguments counts
  as the value it returns (``hash(x) * hash(x) * 0.7`` is ``(h * 0.7) * h``);
- branch_register.py: a local a kept branch leaves in a variable read after it, in that
  variable's register (what a lane outside the branch holds for a derivative);
- added_zero.py: ``fadd(a, 0.0) -> a``, which keeps the sign of a -0.0;
- flrp.py: nir_lower_flrp's formula for a `mix`, chosen from the other `mix` calls;
- lower_precision.py: not a rewrite of the order but of the type, float16 arithmetic on lowp
  lookups (Mesa's lower_precision.cpp), and a lookup's constant arguments rounded to float16.

Constants are what Mesa knows as constants: also a global variable initialised by a constant
expression and never written (queries.py :func:`constant_global`: GLSL IR propagates it).
queries.py holds the questions several families ask (is this a constant, a product, the value
a local holds here, ...); dispatch.py tries the rules on a binary expression in Mesa's order
(one table, read by both engines).

Each rewrite is emitted as ``(<rewritten> if rt.lp else <written>)``: float32 renders take
Mesa's order, float64 (the accuracy reference) and float16 keep the written one. Not copied
(measured, left as written): chains GLSL IR rebalances before NIR sees them, such as
``(a + b + c) + K`` of variables (llvmpipe gives ``(a + b) + (c + K)``: do_rebalance_tree),
other rewrites that reach across a call (NIR inlines every function: followed are an opaque
result, inlined_results.py, a constant added to a returned ``+=`` chain,
:func:`sunk_return`, products by constants merged into a ``dot`` through an argument,
cpu_core/inline.py, and constants a call site passes in, folded and merged through the
callee's arithmetic, matrix products included, for straight-line callees:
cpu_core/call_fold.py, gargantua's camera rotation ``(cos(-0.45)*10) * sin(x)``),
and a squared length that is not followed by a constant sum (``sqrt(a)*sqrt(a)`` stays).

Every function takes the engine that asks (`tr`), typed against cpu_core/fold_protocols.py: a
FoldEngine for the decisions that emit nothing (the compiled engine asks them of a
context.FoldContext), a FoldEmitter for the rewrites that build Mesa's order from the engine's
operations (the NumPy transpiler, and the compiled engine's fold_values.py). Each reads the
program's model, facts, current function and `fold_state` (cpu_core/fold_state.py, the rules'
memo of the program). The code an engine writes of its own for a rule (a chain's base kept in a
temporary, a float16 tree, a call folded per call site) is that engine's: the NumPy transpiler's
in numpy_engine/transpile (binary_rules.py, call_fold.py, float16.py, returned_sums.py,
sum_chains.py), the compiled engine's in compiled_engine/.
"""

from .added_zero import zero_add
from .branch_register import MergedRegister, arm_values, merged_register
from .components import component_write
from .context import FoldContext
from .dispatch import rewrite_binary
from .dot_constants import broadcast_dot, dot_operand, merged_dot
from .exp_log import exp_product
from .ffma_split import fused_plan
from .flrp import mix_form
from .loop_compounds import compound_copies
from .loop_copies import later_values
from .lower_precision import float16_lookup_args
from .ray_dots import RayCall, RayFn, ray_call, ray_dot, ray_fn, ray_loop
from .repeated_sums import (
    Entry,
    call_step,
    chain_globals,
    chain_params,
    indexed_loop,
    later_entry,
    loop_count,
    param_step,
    sum_entry,
)
from .return_register import register_call
from .returned_sums import (
    SunkOrder,
    sunk_call,
    sunk_order,
    sunk_return,
)

__all__ = [
    "FoldContext",
    "MergedRegister",
    "SunkOrder",
    "arm_values",
    "merged_register",
    "exp_product",
    "Entry",
    "call_step",
    "chain_globals",
    "chain_params",
    "indexed_loop",
    "later_entry",
    "later_values",
    "loop_count",
    "broadcast_dot",
    "component_write",
    "compound_copies",
    "dot_operand",
    "merged_dot",
    "float16_lookup_args",
    "fused_plan",
    "mix_form",
    "param_step",
    "RayCall",
    "RayFn",
    "ray_call",
    "ray_dot",
    "ray_fn",
    "ray_loop",
    "register_call",
    "rewrite_binary",
    "sum_entry",
    "sunk_call",
    "sunk_return",
    "sunk_order",
    "zero_add",
]
