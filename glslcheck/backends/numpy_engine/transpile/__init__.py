"""The GLSL-to-Python code generator: a checked Shadertoy program becomes a readable NumPy module.

This module owns the translation of the checked AST (types and symbols come from
`glslcheck.semantics`, never re-derived here) into Python source that calls the runtime
(`glslcheck.backends.numpy_engine.runtime`, lane representation in its docstring). The printer is
many tiny `_print_<Node>` / `_stmt_<Node>` methods; built-ins come from the built-in table; an
unsupported construct (texture lookups, `gl_FragDepth`, ...) is a `GlslError` at its location.

The generated module
====================

* one `def` per GLSL function reachable from `mainImage` (callees first), 4-space indents, a
  `# line N: <GLSL text>` comment before the code of each statement; `shade(S)` is Shadertoy's
  footer (`mainImage(color, fragCoord)`, alpha forced to 1) and `init_globals(S)` runs the
  global initializers once per render;
* every GLSL name is mangled: locals and parameters `v_<name>`, functions `f_<name>`, globals
  `S.g_<name>`, uniforms `S.u_<name>`, struct types `s_<name>`, struct members `m_<name>`
  (the checker's program-wide unique names keep shadowed names apart); generated temporaries
  start with `_`, module constants with `C_`/`Z_`. No GLSL text reaches the code except as
  sanitised comments, so no name can collide with a Python keyword, built-in or the runtime;
* module-level names it uses: `rt` (a `Runtime`), `X` (the lane helpers of `program.py`),
  and its own constants. The host executes it with `__builtins__` empty.

Execution model
===============

All pixels of a tile are lanes. A mask (`_m..`) is `None` ("every lane of the current lane
set") or a bool array; writes under a mask keep the old value elsewhere (`rt.assign`).

* uniform values (the same in every lane: they depend only on constants, uniforms and uniform
  variables; backends/cpu_core/uniformity.py) are arrays of one lane, computed once per tile.
  A write needs no mask where no lane the mask leaves out reads the variable again (declared
  in the same branch, or the others returned: `Uniformity.is_free`), so
  `Light L[4]; L[0] = Light(...);` after an early return stays one value per tile. A run of
  statements that only computes such values, outside loops, is run by the first tile of the
  frame that reaches it and read back by the others (`X.frame` / `X.keep`, frame_values.py).
* `if`/`?:`/`&&`/`||` with a lane-dependent condition run each side under its mask, and only
  when some lane takes it. A uniform condition is a plain Python `if`.
* loops keep `_live` (lanes still looping): the condition, `break` and `return` remove lanes;
  `continue` sets `_cnt` for the rest of the iteration. The Python loop ends when no lane is
  live. A `for` loop's induction variable (declared in the init, changed only by the step) is
  stepped unmasked, so a loop such as `for (int i = 0; i < 64; i++)` stays uniform even when
  lanes `break` at different times. Each loop execution stops after `LOOP_CAP` iterations with
  a GlslError naming the loop's line.
* `switch`: lanes fall through from their matching label (`_fall`) until a `break`.
* `return` inside control flow accumulates the value in `_rv` and the lanes in `_ret`; after a
  statement that can disable lanes the current mask is refreshed and the rest of the block is
  nested under `if X.live(mask):`, so code no lane reaches costs nothing.
* `discard` marks `S.discard` and returns from every function on the call stack; discarded
  pixels keep the framebuffer's clear value (0, 0, 0, 0), as the GL backend does.
* out/inout arguments: arguments are evaluated left to right once (index expressions of an
  l-value included); the callee returns `(value, out1, out2, ...)` and the caller copies the
  outs back under its own mask, left to right. `out` parameters start at zero.
* undefined values: an `out` parameter and a local without an initializer start at zero, as
  WebGL's; with `Transpiler(..., undefined="vary")` the ones the checker finds read before
  written (semantics.analysis.undefined.origins), and the operations on constants outside their
  range, get a value drawn anew at each (`X.undefined`, tiles.py) instead: verify renders both
  modules to find the pixels that depend on them. The normal module is unchanged by the option.
* `pow` with a constant exponent of 1.0, 2.0, 4.0 or +0.0 (per vector component) or a constant
  base of ones is emitted as Mesa compiles it (`rt.pow_const`, `rt.pow_one`): products instead
  of `exp2(y*log2(x))`, so `pow(-0.5, 2.0)` is 0.25 as on llvmpipe, not NaN.
* constant expressions inside functions (`vec3(0.6)`, `-1.0`, constant arrays and structs) are
  module constants `C_x<n>`, computed once when the module is executed; float arithmetic and
  comparisons print as NumPy operators (`(a * b)`: the runtime's ufuncs without a call).
* a function ending in `if (c) return K; return e;` (K constant, no side effects) returns
  `rt.select(c, K, e)` without a return mask: `e` runs on every lane, unless c holds in every
  lane (a tile of pixels that all miss a sphere), which returns K without computing `e`.
* compaction: when fewer than half of the lanes of a varying branch or loop iteration are
  active (and there are enough lanes to matter), the values the region uses are gathered to the
  active lanes (`X.gather` / `X.push`), the region runs on the short arrays with no mask, and the
  values are scattered back afterwards (globals and fragment coordinates are gathered on first
  read). Regions that use derivatives are never compacted. Two kinds of values are not put back
  into the lanes: a uniform local keeps the one value the region wrote (its writes there are
  free), and a local used only in this branch of a varying `if` (`Uniformity.dead_after`) is
  left as the region ended: no lane reads it again. So `PointLight L[4];` declared before
  `if (hit) { L[0] = ...; ... }` is not broadcast to every lane of the tile at the branch's end.
"""

# The passes, one module each (a newcomer reads them in this order):
#   common.py       limits, names and helpers every pass shares
#   (../../cpu_core: facts.py, the static facts; uniformity.py, which values are the same in every
#   lane; nir_fold/, call_fold.py, inline.py, constant_flow.py, Mesa's rewrites, shared with the
#   compiled engine)
#   names.py        mangled names, module constants and zero values
#   expressions.py  expressions and l-values
#   statements.py   statements, control flow, loops and compaction
#   frame_values.py the statements computed once a frame, not once a tile
#   functions.py    functions and calls
#   limits.py       Python's limits (spilling, outlining) and the lane-state estimate
#   binary_rules.py, call_fold.py, float16.py, returned_sums.py, sum_chains.py: the code this
#                   transpiler writes of its own for the rewrites of ../../cpu_core/nir_fold
#   module.py       the Transpiler and the module it writes; transpile(), transpile_shader()

from ...cpu_core.common import LOOP_CAP
from .common import (
    OUTLINE_EXPR_INDENT,
    OUTLINE_INDENT,
    OUTLINE_LOOPS,
    SMALL_STATE,
    SPILL_HEIGHT,
    check_program,
)
from .limits import PythonLimits, compile_generated, glsl_location, lane_state, too_complex
from .module import Transpiled, Transpiler, transpile, transpile_shader
from .state import FnState, LoopCtx, LValue

__all__ = [
    "LOOP_CAP",
    "OUTLINE_EXPR_INDENT",
    "OUTLINE_INDENT",
    "OUTLINE_LOOPS",
    "SMALL_STATE",
    "SPILL_HEIGHT",
    "check_program",
    "LValue",
    "FnState",
    "PythonLimits",
    "glsl_location",
    "compile_generated",
    "lane_state",
    "too_complex",
    "Transpiled",
    "Transpiler",
    "transpile",
    "transpile_shader",
    "LoopCtx",
]
