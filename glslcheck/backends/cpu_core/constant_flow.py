"""Which variables may hold a compile-time constant with a zero component once Mesa has
inlined every function: the float32 path's view through constant function arguments.

Mesa compiles a GLSL program by inlining every function into main (glsl_to_nir, then
nir_inline_functions) before nir_opt_constant_folding and nir_opt_algebraic run (Mesa 22.3,
src/compiler/nir/nir_opt_algebraic.py). So a constant argument is a literal inside the
inlined body, and the algebraic rules apply to it: ``rayEval(dir, vec4(0, 0, 0, 1), t)``
computing ``origin + t * dir`` is ``t * dir`` in x, y and z (``fadd(a, 0.0) -> a``, which keeps
a -0.0 that IEEE addition makes +0.0). The NumPy backend does not inline: a function is one
Python function for every call. At run time a constant argument is still visible (a
lane-uniform array that is not a uniform input: ``Runtime._const``), so the runtime applies the
rule (``Runtime.fadd``); this module tells the code generator where it has to ask, so every
other addition stays a plain NumPy operator.

The analysis is a fixed point over the whole program. A symbol (local, parameter, out
parameter) may hold a constant zero when some write gives it a value that may be one:

- a constant expression with a zero component (``0.0``, ``vec4(0.0, 0.0, 0.0, 1.0)``);
- a plain read (a variable, a field, a component, an element) of such a symbol;
- a call of a user function that may return one;
- for a parameter: such an argument at some call site; for a variable passed as an out or
  inout argument: the callee's parameter may hold one.

"May": a symbol in the set can hold other values too; the runtime checks the value it got.
"""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...semantics.analysis import param_directions, written_variable
from ...semantics.model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ...semantics.model import Model
    from .fold_protocols import FoldEngine


class ConstantFlow:
    """`ConstantFlow(model)`: `may_be_zero_constant(node)` for any expression of the program."""

    def __init__(self, model: Model) -> None:
        self.model = model
        self.symbols: set[int] = set()  # ids of symbols that may hold a constant zero
        self.returns: set[int] = set()  # ids of functions that may return one
        functions = list(model.reachable_functions())
        for sym in model.globals:  # a global initialised by a constant (written or not)
            init = sym.node.init if isinstance(sym.node, A.Declarator) else None
            if init is not None and self.may_be_zero_constant(init):
                self._add(sym)
        changed = True
        while changed:
            before = (len(self.symbols), len(self.returns))
            for fn in functions:
                self._function(fn)
            changed = (len(self.symbols), len(self.returns)) != before

    def may_be_zero_constant(self, node: Any) -> bool:
        """The value of `node` may be a compile-time constant with a zero component."""
        value = self.model.const_value(node)
        if value is not None:
            return _has_zero(value)
        if isinstance(node, A.Call):
            tgt = self.model.call_target(node)
            return isinstance(tgt, Symbol) and id(tgt) in self.returns
        while isinstance(node, (A.Field, A.Index)):
            node = node.base
        if isinstance(node, A.Identifier):
            sym = self.model.symbol_of(node)
            return sym is not None and id(sym) in self.symbols
        return False

    def _function(self, fn: Symbol) -> None:
        m = self.model
        for n in fn.node.body.walk():
            if (
                isinstance(n, A.Declarator)
                and n.init is not None
                and self.may_be_zero_constant(n.init)
            ):
                self._add(m.symbol_of(n))
            elif isinstance(n, A.Assignment) and n.op == "=" and self.may_be_zero_constant(n.value):
                self._add(written_variable(m, n.target)[0])
            elif (
                isinstance(n, A.Return)
                and n.value is not None
                and self.may_be_zero_constant(n.value)
            ):
                self.returns.add(id(fn))
            elif isinstance(n, A.Call):
                tgt = m.call_target(n)
                if not isinstance(tgt, Symbol):
                    continue
                for arg, p, d in zip(n.args, tgt.node.proto.params, param_directions(tgt)):
                    psym = m.symbol_of(p)
                    if d != "out" and self.may_be_zero_constant(arg):
                        self._add(psym)
                    if d != "in" and psym is not None and id(psym) in self.symbols:
                        self._add(written_variable(m, arg)[0])

    def _add(self, sym: Symbol | None) -> None:
        if sym is not None:
            self.symbols.add(id(sym))


def _has_zero(value: Any) -> bool:
    if isinstance(value, (tuple, list)):
        return any(_has_zero(v) for v in value)
    return isinstance(value, float) and value == 0.0


def constant_flow(tr: FoldEngine) -> ConstantFlow:
    """The analysis of the transpiler's program, made once."""
    flow = tr.fold_state.constant_flow
    if flow is None:
        flow = tr.fold_state.constant_flow = ConstantFlow(tr.model)
    return flow
