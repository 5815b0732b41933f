"""A variable advanced by constants (cpu_core/nir_fold/repeated_sums.py), written by the
compiled engine's code generator: a step of a chain as ``base + K``, the value before the chain
kept in temporaries, a chain parameter's base and constants passed to the callee as more
arguments, and in an unrolled loop whose copies read different constants, the one of its pass.

`SumChains` is a base class of ExpressionEmitter (expressions.py), whose emission (`read`,
`expr`, `binary_values`, `tmp_copy`, `cf`, `type_of`) its methods use."""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ...semantics.model import Symbol
from ..cpu_core import nir_fold
from .values import Val

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up


def _step_constant(e: A.Assignment) -> Any:
    """The constant of a step ``x += #c`` (``x = x + #c``, ``x = #c + x``, ...)."""
    if e.op != "=":
        return e.value
    assert isinstance(e.value, A.Binary)  # (nir_fold's steps)
    left = e.value.left
    if isinstance(left, A.Identifier) and left.name == _target_name(e):
        return e.value.right
    return left


def _target_name(e: A.Assignment) -> str | None:
    return e.target.name if isinstance(e.target, A.Identifier) else None


def nir_chain_params(gen: Any, fn: Symbol) -> dict[int, Any]:  # index -> sum_order.Program
    """nir_fold.chain_params of user function `fn` (the parameters a caller's ``+= #c`` chain
    runs through), {} outside a function."""

    if gen.fn is None or gen.fn.sym is None:
        return {}
    return nir_fold.chain_params(gen.fold_context(), fn)


class SumChains:
    """The ``+= #c`` chains of ExpressionEmitter (see the module docstring)."""

    if TYPE_CHECKING:  # ExpressionEmitter's and Codegen's
        fn: Any
        indent: int

        def fold_context(self) -> Any: ...
        def read(self, p: Any) -> Any: ...
        def expr(self, e: Any) -> Val: ...
        def type_of(self, e: Any) -> Any: ...
        def binary_values(self, op: str, left: Val, right: Val, e: Any) -> Val: ...
        def tmp_copy(self, p: str) -> str: ...
        def cf(self, v: float) -> str: ...

    def repeated_sum(self, e: A.Assignment, targets: list) -> Val | None:
        """A step of a ``+= #c`` chain: ``base + K``, K from the NumPy backend's plan
        (nir_fold.repeated_sums: Mesa's order, sum_order.py), the base kept at the chain's
        first step; a step of a chain parameter of this function reads the caller's base and
        K (or computes as written when the caller passes none). None for any other write."""

        fn = self.fn
        if fn is None or fn.sym is None or any(not isinstance(p, str) for p in targets):
            return None
        ctx = self.fold_context()
        later = nir_fold.later_entry(ctx, e)
        first = self.chain_step(e, targets, nir_fold.sum_entry(ctx, e), True)
        if later is None:
            return first
        # (a first-copy loop: its first pass continues the chain, the later ones start afresh)
        rest = self.chain_step(e, targets, later[1], False) or self.written_step(e, targets)
        first = first or self.written_step(e, targets)
        ix = fn.sum_index[id(later[0])]
        return Val(
            first.t,
            [f"({a} if {ix} == 0 else {b})" for a, b in zip(first.parts, rest.parts)],
        )

    def written_step(self, e: A.Assignment, targets: list) -> Val:
        """A step of a chain as written: the old value plus the constant."""
        old = Val(self.type_of(e.target), [self.read(p) for p in targets])
        if e.op == "=":  # x = x + #c
            assert isinstance(e.value, A.Binary)
            op = e.value.op
        else:  # x += #c
            op = e.op[:-1]
        return self.binary_values(op, old, self.expr(_step_constant(e)), e)

    def chain_step(self, e: A.Assignment, targets: list, entry: Any, own: bool) -> Val | None:
        """A step's ``base + K`` from a chain parameter's caller (`own`) or from `entry`."""
        ctx = self.fold_context()
        mine = nir_fold.param_step(ctx, e) if own else None
        if mine is not None:
            i = mine[0]
            written = self.written_step(e, targets)
            k = self.param_k(mine, 0)
            return Val(written.t, [f"((_c{i}b + {k}) if _c{i}f else {written.parts[0]})"])
        base = self.chain_base(entry, [self.read(p) for p in targets])
        if entry is None or base is None:
            return None
        ks = [
            self.k_code(entry, [self.cf(float(k[c])) for k in entry.ks]) for c in range(len(base))
        ]
        return Val(self.type_of(e.target), [f"({b} + {k})" for b, k in zip(base, ks)])

    def chain_base(self, entry: Any, old: list | None) -> list | None:
        """The value before the entry's chain, kept in temporaries at its first write (`old`:
        the value there), defined where it is read (not inside a deeper block)."""
        if entry is None or self.fn is None:
            return None
        if entry.root and old is not None:
            self.fn.sum_chains[(entry.chain, id(entry.sym))] = (
                [self.tmp_copy(p) for p in old],
                self.indent,
            )
        known = self.fn.sum_chains.get((entry.chain, id(entry.sym)))
        return known[0] if known is not None and known[1] <= self.indent else None

    def param_k(self, own: tuple, m: int) -> str:
        """The m-th K of a write of this function's chain parameter (nir_fold.param_step): its
        slot's argument, or in an unrolled loop the copies' arguments indexed by its pass."""

        i, at, stride, loop, _ = own
        if loop is None:
            return f"_c{i}k{at + m}"
        assert self.fn is not None
        copies = nir_fold.loop_count(self.fold_context(), loop)
        names = [f"_c{i}k{at + m + stride * j}" for j in range(copies)]
        if len(names) == 1:  # (a first-copy loop: only its first pass reads the caller's K)
            return names[0]
        return f"({', '.join(names)})[{self.fn.sum_index[id(loop)]}]"

    def k_code(self, entry: Any, codes: list[str]) -> str:
        """One constant per copy of the unrolled loop around the entry, indexed by its pass
        where they differ."""
        if len(codes) == 1:
            return codes[0]
        assert self.fn is not None
        return f"({', '.join(codes)})[{self.fn.sum_index[id(entry.loop)]}]"

    def chain_args(self, e: A.Call, fn: Symbol, inouts: dict[int, str]) -> list[str]:
        """The chain arguments of a call of `fn` (nir_fold.chain_params), for each such
        parameter a flag, the base and one K per constant its callee adds: the caller's chain
        (or its own chain parameter passed on), or a false flag and zeros (the callee computes
        as written); `inouts`: each such argument's value, kept in a temporary."""

        if self.fn is None or self.fn.sym is None:
            return []
        ctx = self.fold_context()
        later = nir_fold.later_entry(ctx, e)
        first = self.chain_call_args(e, fn, inouts, nir_fold.sum_entry(ctx, e), True)
        if later is None:
            return first
        rest = self.chain_call_args(e, fn, inouts, later[1], False)
        ix = self.fn.sum_index[id(later[0])]
        return [f"({a} if {ix} == 0 else {b})" for a, b in zip(first, rest)]

    def chain_call_args(
        self, e: A.Call, fn: Symbol, inouts: dict[int, str], entry: Any, own_chain: bool
    ) -> list[str]:
        """:meth:`chain_args` from the caller's chain parameter (`own_chain`) or `entry`."""
        ctx = self.fold_context()
        params = nir_fold.chain_params(ctx, fn)
        zero = self.cf(0.0) if params else ""
        out: list[str] = []
        for i, program in sorted(params.items()):
            step = nir_fold.call_step(ctx, e)
            mine = step is not None and step[0] == i
            own = nir_fold.param_step(ctx, e) if mine and own_chain else None
            if own is not None:
                j = own[0]
                out += [f"_c{j}f", f"_c{j}b"] + [self.param_k(own, m) for m in range(own[4])]
                continue
            entry = entry if mine else None
            base = self.chain_base(entry, [inouts[i]] if i in inouts else None)
            if entry is None or base is None:
                out += ["False", zero] + [zero] * program.slots()
                continue
            out += ["True", base[0]]
            out += [
                self.k_code(entry, [self.cf(float(c[m])) for c in entry.ks])
                for m in range(program.slots())
            ]
        return out
