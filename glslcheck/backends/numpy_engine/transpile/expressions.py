"""Expressions and l-values: operators, constructors, built-in calls (Mesa's `pow` rewrites),
ternaries and short-circuit operators over lanes, constant expressions hoisted to module
constants, and reads and masked writes through fields, swizzles and indices. Mixed into
`Transpiler`."""

from __future__ import annotations

import re
from typing import Any

from ....base.precision import float32_literal
from ....frontend import syntax as A
from ....frontend.printer import to_glsl
from ....language import builtin_functions as B
from ....language import glsl_types as T
from ....semantics.analysis import param_directions
from ....semantics.model import Constructor, Symbol
from ...cpu_core import nir_fold
from ...cpu_core.common import (
    CUBE_FUNCTIONS,
    DERIVATIVES,
    IDENT,
    IMPLICIT_LOD,
    RUNTIME_NAMES,
    TEXTURE_FUNCTIONS,
    fold_tree,
)
from ...cpu_core.facts import is_plain_read
from ...cpu_core.inline import bound_code
from .binary_rules import binary
from .common import (
    _BIN_METHODS,
    _FLOAT_OPERATORS,
    OUTLINE_EXPR_INDENT,
    SPILL_HEIGHT,
    _components,
    _error,
    _is_constant_text,
)
from .ray_dots import ray_dot_code, ray_normalize
from .returned_sums import keep_term
from .state import LValue, TranspilerState
from .sum_chains import repeated_sum

# Built-ins whose runtime method, on float operands, is one NumPy ufunc (Runtime.np_*): called
# directly, as `rt.np_fmin(a, b)`, without the method's Python frame (`Runtime.min_` ...)
_FLOAT_UFUNCS = {
    "min": "np_fmin",
    "max": "np_fmax",
    "abs": "np_abs",
    "sqrt": "np_sqrt",
    "floor": "np_floor",
    "ceil": "np_ceil",
    "trunc": "np_trunc",
}
# Operators that are NumPy's operator on two int or two uint operands (int32 and uint32 arrays,
# as constants and every runtime result are): rt.add is np.add, rt.bit_xor np.bitwise_xor ...
# (`/` and `%` have GLSL's own rules for zero and signs; `<<` on int goes through unsigned bits)
_INT_OPERATORS = ("+", "-", "*", "<", "<=", ">", ">=", "&", "|", "^")
_TEMPORARY = re.compile(r"_t\d+(\[\d+\])?")  # a temporary (or a call's result in one): computed


def _own_mask(e: Any) -> bool:
    """A `?:`, `&&` or `||`: its parts may run under masks of their own, so the calls they
    repeat are shared within them only (`Expressions.expr`, `repeated_calls`)."""
    return isinstance(e, A.Ternary) or (isinstance(e, A.Binary) and e.op in ("&&", "||"))


class Expressions(TranspilerState):
    """The expression pass of `Transpiler`."""

    # Repeated built-in calls of the expression being printed (`repeated_calls`): (ids of the
    # Call nodes, {printed call: the temporary holding its value}); None outside such an expression
    cse: tuple[set[int], dict[str, str]] | None = None
    CSE_CALLS = True  # off in the tracing transpiler (tracing.py), which reports every operation

    # -- expressions ---------------------------------------------------------------------------
    def expr(self, e: Any, mask: str | None) -> str:
        if (
            (self.cse is None or _own_mask(e))
            and self.CSE_CALLS
            and self.fn is not None
            and not self.in_const
        ):
            # an expression without side effects (or a part evaluated under a mask of its own):
            # the calls it repeats, shared by its parts (an empty set: none to share)
            saved, self.cse = (
                self.cse,
                None if self.has_effects(e) else (self.repeated_calls(e), {}),
            )
            try:
                text = self.print_expr(e, mask)
            finally:
                self.cse = saved
        else:
            text = self.print_expr(e, mask)
        if (
            self.fn is not None
            and not self.in_const
            and self.facts.order.needs_temp(e)
            and not _TEMPORARY.fullmatch(text)
        ):
            # Mesa computes e here, before a later part of the statement writes what it reads
            # (cpu_core/eval_order.py): not when the statement's text is evaluated
            return self.tmp(text)
        return text

    def print_expr(self, e: Any, mask: str | None) -> str:
        method = getattr(self, "_print_" + type(e).__name__, None)
        if method is None:
            raise _error(
                f"{type(e).__name__} expressions are not supported by the NumPy backend", e
            )
        if self.too_deep(OUTLINE_EXPR_INDENT, loops=False):
            value = self.outline(lambda: self.expr(e, mask), e)
            assert value is not None  # what build returns: the expression's value
            return value
        if id(e) in self.undefined_origins and self.fn is not None:
            # an operation whose value GLSL leaves undefined, in the "vary" mode (module.py)
            return f"X.undefined(S, {self.zero(self.type_of(e), e)})"
        if self.fn is None or self.in_const or self.model.const_value(e) is None:
            return self.spill(e, method(e, mask))
        # a constant expression inside a function: computed once, as a module constant (the
        # same runtime calls at import time instead of on every call in every tile)
        self.in_const = True
        n_lines = len(self.lines)
        try:
            text = method(e, mask)
        finally:
            self.in_const = False
        if len(self.lines) != n_lines or "(" not in text or not _is_constant_text(text):
            return self.spill(e, text)
        name = self.const_exprs.get(text)
        if name is None:
            name = self.const_exprs[text] = f"C_x{len(self.const_exprs) + 1}"
            self.consts[name] = text
        return name

    def repeated_calls(self, e: Any) -> set[int]:
        """The built-in calls that `e` (an expression without side effects: `expr` asks)
        makes more than once with the same arguments (the same GLSL text), leaving out the
        parts under a `&&`, `||` or `?:` inside it, which `expr` treats as expressions of their
        own (they may run under masks of their own). `mat2(cos(a), -sin(a), sin(a), cos(a))`,
        a rotation in most raymarchers, computes cos(a) and sin(a) once each, as Mesa's CSE
        does (the llvmpipe emulation of one sin is about 40 NumPy calls). The first is kept in
        a temporary emitted before the expression's line, which every later one reads; its
        value is the same bits, since nothing in e writes a variable in between."""
        groups: dict[str, list[Any]] = {}
        stack = [e]
        while stack:
            n = stack.pop()
            if n is not e and _own_mask(n):
                continue  # a part under a mask of its own: its calls are its own (`expr`)
            if isinstance(n, A.Call) and not isinstance(
                self.model.call_target(n), (Constructor, Symbol)
            ):
                groups.setdefault(to_glsl(n), []).append(n)
            stack.extend(n.children())
        return {
            id(n)
            for g in groups.values()
            if len(g) > 1
            for n in g
            if self.model.const_value(n) is None
        }

    def type_of(self, e: Any) -> Any:
        return self.model.type_of(e)

    def needs_hoist(self, e: Any) -> bool:
        """True when evaluating e emits statements (so earlier operands go to temporaries
        first): effects, or a part high enough to be spilled (`PythonLimits.spill`)."""
        return self._height(e) >= SPILL_HEIGHT or fold_tree(e, self._hoists, self._hoists_here)

    def _hoists_here(self, n: Any, kids: list[bool]) -> bool:
        if any(kids) or isinstance(n, (A.Assignment, A.Sequence)):
            return True
        if isinstance(n, (A.Unary, A.Postfix)) and n.op in ("++", "--"):
            return True
        if isinstance(n, A.Call):
            tgt = self.model.call_target(n)
            if any(d != "in" for d in param_directions(tgt)):
                return True
            if isinstance(tgt, Symbol) and id(tgt) in self.facts.may_discard:
                return True
        if isinstance(n, (A.Ternary, A.Binary)) and (
            not isinstance(n, A.Binary) or n.op in ("&&", "||")
        ):
            if self.has_effects(n.then if isinstance(n, A.Ternary) else n.right) or (
                isinstance(n, A.Ternary) and self.has_effects(n.else_)
            ):
                return True
        return False

    def has_effects(self, e: Any) -> bool:
        return self.side_effects(e)

    def tmp(self, value: str) -> str:
        if value.startswith(("C_", "Z_")) and value.replace("_", "").isalnum():
            return value
        t = self.fresh("t")
        self.emit(f"{t} = {value}")
        return t

    def exprs(self, items: list[Any], mask: str | None) -> list[str]:
        """Evaluate expressions as Mesa does: a later operand's side effects (calls with out
        arguments or global writes, assignments, ++/--) are emitted as statements first and a
        variable, swizzle, index or operator is read after them, so `vec4(ip, modf(x, ip),
        ...)` and `vec2(i, i++)` see the updated value in every position (measured on
        llvmpipe; GLSL IR hoists such calls and reads variables lazily). A call, a constructor
        or a `?:` before them is computed where it stands (`expr`, cpu_core/eval_order.py)."""
        return [self.expr(e, mask) for e in items]

    def _print_IntLiteral(self, e: A.IntLiteral, mask: str | None) -> str:
        return self.const_int(e.value, e.unsigned or self.type_of(e) == T.UINT)

    def _print_FloatLiteral(self, e: A.FloatLiteral, mask: str | None) -> str:
        return self.const_float(e.value, float32_literal(e.text) if e.text else None)

    def _print_BoolLiteral(self, e: A.BoolLiteral, mask: str | None) -> str:
        return self.const_bool(e.value)

    def _print_Identifier(self, e: A.Identifier, mask: str | None) -> str:
        sym = self.model.symbol_of(e)
        if sym is None:
            raise _error(f"'{e.name}' has no symbol", e)
        bound = bound_code(self, sym)  # a parameter of an inlined call (inline.py)
        return bound if bound is not None else self.var_name(sym, e)

    def _print_Binary(self, e: A.Binary, mask: str | None) -> str:
        folded = binary(self, e, mask)  # Mesa's reassociations (llvmpipe mode)
        if folded is not None:
            return folded
        op = e.op
        if op in ("&&", "||") and (self.has_effects(e.right) or not is_plain_read(e.right)):
            # the right side only where the left does not decide: skipped when no lane needs
            # it (`t > 0.0 && t < best` in a tile where every t is -1)
            return self.short_circuit(e, mask)
        left, right = self.exprs([e.left, e.right], mask)
        if nir_fold.zero_add(self, e):  # x + 0.0 is x on llvmpipe (nir_fold)
            return f"rt.{'fadd' if e.op == '+' else 'fsub'}({left}, {right})"
        lt, rtp = self.type_of(e.left), self.type_of(e.right)
        if op in ("==", "!="):
            if lt.is_scalar and rtp.is_scalar:
                if lt.base == rtp.base and lt.base in ("float", "int", "uint"):
                    return f"({left} {op} {right})"  # np.equal / np.not_equal, as rt.eq and rt.ne
                return f"rt.{'eq' if op == '==' else 'ne'}({left}, {right})"
            return f"rt.{'equal_all' if op == '==' else 'nequal_all'}({left}, {right})"
        if (
            op == "%"
            and self.model.const_value(e.left) is not None
            and self.model.const_value(e.right) is not None
        ):
            return f"rt.rem_const({left}, {right})"
        if op not in _BIN_METHODS and op != "%":
            raise _error(f"the operator '{op}' is not supported", e)
        if op in ("<<", ">>") and (op == ">>" or lt.base == "uint"):
            count = self.model.const_value(e.right)
            if isinstance(count, int) and not isinstance(count, bool) and 0 <= count < 32:
                # a constant count in range (xorshift's `state << 13`): NumPy's shift with the
                # count in the left operand's type, which is what rt.shl / rt.shr compute
                # (for uint; `>>` of an int is arithmetic in both). `int << n` keeps rt.shl,
                # which shifts the unsigned bits (a signed overflow is undefined in C)
                return f"({left} {op} {self.const_int(count, lt.base == 'uint')})"
        return self.binary_values(op, lt, rtp, left, right)

    def short_circuit(self, e: A.Binary, mask: str | None) -> str:
        left = self.tmp(self.expr(e.left, mask))
        res = self.fresh("t")
        self.emit(f"{res} = {self.const_bool(e.op == '||')}")
        m = self.fresh("m")
        self.emit(f"{m} = X.{'and_' if e.op == '&&' else 'andnot'}({mask}, {left})")
        self.emit(f"if X.live({m}):")
        self.indent += 1
        right = self.expr(e.right, m)
        self.emit(f"{res} = {right}")
        self.indent -= 1
        return f"rt.{'and_' if e.op == '&&' else 'or_'}({left}, {res})"

    def _print_Unary(self, e: A.Unary, mask: str | None) -> str:
        if e.op in ("++", "--"):
            return self.incdec(e, mask, want_value=True)
        v = self.expr(e.operand, mask)
        if e.op == "-":
            return f"(-{v})" if self.type_of(e.operand).base == "float" else f"rt.neg({v})"
        if e.op == "+":
            return v
        if e.op == "!":
            return f"rt.not_({v})"
        if e.op == "~":
            return f"rt.bit_not({v})"
        raise _error(f"the operator '{e.op}' is not supported", e)

    def _print_Postfix(self, e: A.Postfix, mask: str | None) -> str:
        return self.incdec(e, mask, want_value=True)

    def incdec(self, e: Any, mask: str | None, want_value: bool) -> str:
        lv = self.lvalue(e.operand, mask)
        old = (
            self.tmp(self.read(lv)) if (want_value and isinstance(e, A.Postfix)) else self.read(lv)
        )
        fn = "inc" if e.op == "++" else "dec"
        new = f"rt.{fn}({old})"
        if want_value and isinstance(e, A.Unary):
            new = self.tmp(new)
        self.write(lv, new, mask)
        return old if isinstance(e, A.Postfix) else new

    def _print_Assignment(self, e: A.Assignment, mask: str | None) -> str:
        return self.assignment(e, mask, want_value=True)

    def _nonzero_literal(self, text: str) -> bool:
        """``text`` is a float literal's module constant (`Names.const_float`: ``C_f_0p25``)
        that is not zero in float16 either (float16 keeps nothing below 2**-24; a literal of
        1e-10 is a zero there, which Runtime.fmul folds). NaN is not zero."""
        v = self.float_consts.get(text)
        return v is not None and not abs(v) < 2.0**-24

    def assignment(self, e: A.Assignment, mask: str | None, want_value: bool) -> str:
        lv = self.lvalue(e.target, mask)
        value = nir_fold.compound_copies(self, e, mask, self.read(lv))  # x op= #k, merged
        if value is None:
            value = nir_fold.component_write(self, e, mask, self.read(lv))  # NIR's per component
        if value is None:
            value = repeated_sum(self, e, mask, self.read(lv))
        if value is None:
            value = keep_term(self, e, self.expr(e.value, mask))
            if e.op != "=":
                value = self.binary_values(
                    e.op[:-1], self.type_of(e.target), self.type_of(e.value), self.read(lv), value
                )
        if want_value:
            value = self.tmp(value)
        self.write(lv, value, mask)
        return value

    def binary_values(self, op: str, lt: Any, rtp: Any, left: str, right: str) -> str:
        """`left op right` for operand types lt, rtp (matrix products by shape)."""
        if op == "*" and (lt.is_matrix or rtp.is_matrix):
            if lt.is_matrix and rtp.is_matrix:
                return f"rt.mat_mul_mat({left}, {right})"
            if lt.is_matrix and rtp.is_vector:
                return f"rt.mat_mul_vec({left}, {right})"
            if lt.is_vector and rtp.is_matrix:
                return f"rt.vec_mul_mat({left}, {right})"
        if op == "%":
            return f"rt.rem({left}, {right})"
        if op == "*" and lt.base == "float" and rtp.base == "float":
            if not (self._nonzero_literal(left) or self._nonzero_literal(right)):
                return f"rt.fmul({left}, {right})"  # NaN times a constant zero is 0 (Runtime.fmul)
            # a float literal that is not zero (in any precision) is a constant operand with no
            # zero component: Runtime.fmul would only multiply, so the operator does, without
            # a Python call and two tests per operation (121 of elephant Buffer A's 266 products)
            return f"({left} * {right})"
        if op in _FLOAT_OPERATORS and lt.base == "float" and rtp.base == "float":
            # float operands are always arrays of the render dtype: NumPy's operator is exactly
            # the runtime's ufunc (rt.add is np.add ...), without a Python call per operation
            return f"({left} {op} {right})"
        if op in _INT_OPERATORS and lt.base == rtp.base and lt.base in ("int", "uint"):
            return f"({left} {op} {right})"  # the same, for int32 or uint32 arrays
        return f"rt.{_BIN_METHODS[op]}({left}, {right})"

    # The operations nir_fold's rules build Mesa's order from (fold_protocols.FoldEmitter).
    @staticmethod
    def ieee(op: str, left: str, right: str) -> str:
        """`left op right` of two float values, IEEE (NumPy's operator: no constant folding)."""
        return f"({left} {op} {right})"

    @staticmethod
    def negate(value: str) -> str:
        return f"(-{value})"

    @staticmethod
    def llvmpipe(rewritten: str, written: str) -> str:
        """Mesa's order in float32 (llvmpipe) mode, the written one in float64 and float16."""
        return f"({rewritten} if rt.lp else {written})"

    def store(self, target: str, value: str) -> str:
        """value into the temporary `target` (made before a loop: loop_copies.later_values)."""
        self.emit(f"{target} = {value}")
        return target

    def by_copy(self, loop: Any, first: str, later: str) -> str:
        """`first` in the first pass of a loop NIR unrolls, `later` in the others (its pass
        count: repeated_sums.indexed_loop)."""
        return f"({first} if {self.fold_state.sum_index[id(loop)]} == 0 else {later})"

    @staticmethod
    def component(value: str, i: int) -> str:
        """Component i of a vector value (a view: NumPy's lane arrays are component first)."""
        return f"{value}[{i}]"

    @staticmethod
    def vector(parts: list[str]) -> str:
        """The float vector of these scalar values."""
        return f"rt.vec({len(parts)}, {', '.join(parts)})"

    @staticmethod
    def leaves(value: str, t: Any) -> list[str]:
        """The codes of a float value's scalars (a matrix column by column)."""
        if t.is_scalar:
            return [value]
        if t.is_vector:
            return [f"{value}[{i}]" for i in range(t.size)]
        return [f"{value}[{c}][{r}]" for c in range(t.cols) for r in range(t.rows)]

    @staticmethod
    def swizzle(value: str, idx: tuple[int, ...]) -> str:
        return f'rt.swizzle({value}, "{"".join("xyzw"[i] for i in idx)}")'

    @staticmethod
    def runtime(name: str, *args: str) -> str:
        """A call of the Runtime's operation `name` (fold_values.RUNTIME: those the rules use)."""
        return f"rt.{name}({', '.join(args)})"

    def _print_Ternary(self, e: A.Ternary, mask: str | None) -> str:
        fs = self.fn
        assert fs is not None  # generating a function's body
        effects = self.has_effects(e.then) or self.has_effects(e.else_)
        if not effects:
            if fs is not None and fs.uni is not None and fs.uni.is_uniform(e.cond):
                c = self.expr(e.cond, mask)
                if self.needs_hoist(e.then) or self.needs_hoist(e.else_):
                    c = self.tmp(c)
                a = self.expr(e.then, mask)
                b = self.expr(e.else_, mask)
                return f"({a} if X.true({c}) else {b})"
            c, a, b = self.exprs([e.cond, e.then, e.else_], mask)
            return f"{self.select_fn(e)}({c}, {a}, {b})"
        c = self.tmp(self.expr(e.cond, mask))
        t = self.type_of(e)
        res_a, res_b = self.fresh("t"), self.fresh("t")
        for res, branch, how in ((res_a, e.then, "and_"), (res_b, e.else_, "andnot")):
            self.emit(f"{res} = {self.zero(t, e)}")
            m = self.fresh("m")
            self.emit(f"{m} = X.{how}({mask}, {c})")
            self.emit(f"if X.live({m}):")
            self.indent += 1
            self.emit(f"{res} = {self.expr(branch, m)}")
            self.indent -= 1
        return f"{self.select_fn(e)}({c}, {res_a}, {res_b})"

    def select_fn(self, e: A.Ternary) -> str:
        """`rt.select`, or for a value that is one array (no struct in it) np.where itself, which
        is all that rt.select does with one, without its Python frame."""
        t = self.type_of(e)
        while t.is_array:
            t = t.element
        return "rt.select" if t.is_struct else "rt.np_where"

    def _print_Sequence(self, e: A.Sequence, mask: str | None) -> str:
        for x in e.exprs[:-1]:
            self.effect(x, mask)
        return self.expr(e.exprs[-1], mask)

    def _print_Index(self, e: A.Index, mask: str | None) -> str:
        base, idx = self.exprs([e.base, e.index], mask)
        cv = self.model.const_value(e.index)
        bt = self.type_of(e.base)
        if isinstance(cv, int) and not isinstance(cv, bool):
            if bt.is_array and bt.element.is_struct:
                return f"rt.index({base}, {cv})"
            return f"{base}[{cv}]"
        return f"rt.index({base}, {idx})"

    def _print_Field(self, e: A.Field, mask: str | None) -> str:
        bt = self.type_of(e.base)
        if bt.is_struct and isinstance(e.base, A.Index) and self.type_of(e.base.base).is_array:
            # `a[i].f`: an array of structs is a Struct of arrays, so the one field's array is
            # indexed (one gather) rather than every field and then one of them kept
            arr, at = self.exprs([e.base.base, e.base.index], mask)
            cv = self.model.const_value(e.base.index)
            if isinstance(cv, int) and not isinstance(cv, bool):
                at = str(cv)
            return f'rt.index(rt.field({arr}, "{self.member(e.name, e)}"), {at})'
        base = self.expr(e.base, mask)
        if bt.is_struct:
            return f'rt.field({base}, "{self.member(e.name, e)}")'
        idx = self.model.swizzle_indices(e)
        if bt.is_scalar:
            return base if len(idx) == 1 else f'rt.swizzle({base}, "{"x" * len(idx)}")'
        if len(idx) == 1:
            return f"{base}[{idx[0]}]"
        return f'rt.swizzle({base}, "{"".join("xyzw"[i] for i in idx)}")'

    def _print_MethodCall(self, e: A.MethodCall, mask: str | None) -> str:
        bt = self.type_of(e.base)
        if e.name == "length":
            if bt.is_array:
                return self.const_int(bt.array_size, False)
            if bt.is_vector:
                return self.const_int(bt.size, False)
            if bt.is_matrix:
                return self.const_int(bt.cols, False)
        raise _error(f"the method '.{e.name}()' is not supported", e)

    def _print_Call(self, e: A.Call, mask: str | None) -> str:
        tgt = self.model.call_target(e)
        if isinstance(tgt, Constructor):
            return self.constructor(e, tgt.type, mask)
        if isinstance(tgt, Symbol):
            return self.user_call(e, tgt, mask)
        if tgt is None:
            raise _error(f"the call of '{e.callee}' was not resolved by the checker", e)
        if self.cse is None or id(e) not in self.cse[0]:
            return self.builtin_call(e, tgt, mask)
        text = self.builtin_call(e, tgt, mask)  # a repeated call (`repeated_calls`)
        done = self.cse[1]
        if text not in done:
            done[text] = self.tmp(text)
        return done[text]

    def b2f_select(self, e: A.Call, mask: str | None) -> str | None:
        """`mix(x, y, w)` whose weight NIR sees as b2f (nir_fold.mix_form's "select") and is
        built of `step()` calls, `float(bool)` and their products: ``rt.mix_b2f`` on the bools
        themselves (`x >= edge` and `&`: no float weight made, no compare of it with 1). The
        operands are printed in their order (x, y, then the weight's, left to right)."""
        w = e.args[2]
        if not self._b2f_tree(w) or nir_fold.mix_form(self, e) != "select":
            return None
        x, y = self.exprs(e.args[:2], mask)
        return f"rt.mix_b2f({x}, {y}, {self._b2f_condition(w, mask)})"

    def _b2f_tree(self, w: A.Node) -> bool:
        if isinstance(w, A.Binary):
            return w.op == "*" and self._b2f_tree(w.left) and self._b2f_tree(w.right)
        if not isinstance(w, A.Call):
            return False
        tgt = self.model.call_target(w)
        if isinstance(tgt, Constructor):  # float(b) of one bool scalar
            return (
                tgt.type.is_scalar
                and tgt.type.base == "float"
                and len(w.args) == 1
                and self.type_of(w.args[0]).is_scalar
                and self.type_of(w.args[0]).base == "bool"
            )
        return (
            tgt is not None
            and not isinstance(tgt, Symbol)
            and getattr(tgt, "name", None) == "step"
            and len(w.args) == 2
        )

    def _b2f_condition(self, w: A.Node, mask: str | None) -> str:
        """The bool of a `_b2f_tree` weight: step(edge, x) is `x >= edge` (NaN: false, as
        step's 0), float(b) is b, a product the `&` of its factors' bools."""
        if isinstance(w, A.Binary):
            left = self._b2f_condition(w.left, mask)
            return f"({left} & {self._b2f_condition(w.right, mask)})"
        assert isinstance(w, A.Call)
        args = self.exprs(w.args, mask)
        return args[0] if len(args) == 1 else f"rt.step_mask({args[0]}, {args[1]})"

    def constructor(self, e: A.Call, t: Any, mask: str | None) -> str:
        args = self.exprs(e.args, mask)
        if t.is_array:
            return f"rt.array({', '.join(args)})"
        if t.is_struct:
            fields = ", ".join(
                f"{self.member(fname, e)}={a}" for (fname, _), a in zip(t.fields, args)
            )
            return f'rt.struct("{self.struct_name(t)}", {fields})'
        if t.is_scalar:
            at = self.type_of(e.args[0])
            a = args[0]
            if at.is_matrix:
                a = f"{a}[0][0]"
            elif at.is_vector:
                a = f"{a}[0]"
            if at.base == t.base:
                return a
            return f"rt.to_{t.base}({a})"
        if t.is_vector:
            fn = {"float": "vec", "int": "ivec", "uint": "uvec", "bool": "bvec"}[t.base]
            return f"rt.{fn}({t.size}, {', '.join(args)})"
        if t.is_matrix:
            return f"rt.mat({t.cols}, {t.rows}, {', '.join(args)})"
        raise _error(f"constructing '{t}' is not supported", e)

    def builtin_call(self, e: A.Call, ov: Any, mask: str | None) -> str:
        name = ov.name
        if (
            getattr(ov, "category", None) == B.TEXTURE
            or name.startswith("texture")
            or name.startswith("texel")
        ):
            sampler = str(self.type_of(e.args[0]))
            if name not in (TEXTURE_FUNCTIONS if sampler == "sampler2D" else CUBE_FUNCTIONS):
                raise _error(
                    f"{name}(): this texture lookup is not supported by the NumPy backend yet",
                    e,
                    help="render this shader with --backend gl",
                )
            width = ", width=S.width" if name in IMPLICIT_LOD else ""
            args = self.exprs(e.args, mask)
            for i in nir_fold.float16_lookup_args(self, e):  # constants as a lowp sampler gets them
                args[i] = f"rt.lowp_constant({args[0]}, {args[i]})"
            return f"rt.{name}({', '.join(args)}{width})"  # textures.py
        quals = list(getattr(ov, "qualifiers", ()) or ())
        if name == "modf":
            x = self.expr(e.args[0], mask)
            lv = self.lvalue(e.args[1], mask)
            r = self.tmp(f"rt.modf({x})")
            self.write(lv, f"{r}[1]", mask)
            return f"{r}[0]"
        if any(q == "out" for q in quals):
            raise _error(f"{name}() with an out parameter is not supported", e)
        if name == "mix":
            selected = self.b2f_select(e, mask)
            if selected is not None:
                return selected
        if name == "normalize":
            kept = ray_normalize(self, e, mask)  # a ray root's v kept (nir_fold.ray_dots)
            if kept is not None:
                return kept
        args = self.exprs(e.args, mask)
        if name == "mix":
            form = nir_fold.mix_form(self, e)  # Mesa's flrp lowering: see nir_fold
            if form is not None:
                args.append(repr(form))  # rt.mix's last argument
        if name == "dot":
            merged = nir_fold.merged_dot(self, e, args, mask)  # constants merged into a dot product
            if merged is None:
                merged = nir_fold.broadcast_dot(
                    self, e, args, mask
                )  # dot(vec2(s), #K): s * (K.x + K.y)
            ray = ray_dot_code(self, e, args, merged)  # a caller's ray's constants merged
            if ray is not None:
                return ray
            if merged is not None:
                return merged
        if name == "exp":
            lowered = nir_fold.exp_product(self, e, args, mask)  # exp2(x * (k * log2(e)))
            if lowered is not None:
                return lowered
        if name == "pow":
            rewritten = self.pow_rewrite(e, args)
            if rewritten is not None:
                return rewritten
        if name in _FLOAT_UFUNCS and all(self.type_of(a).base == "float" for a in e.args):
            return f"rt.{_FLOAT_UFUNCS[name]}({', '.join(args)})"
        if name == "clamp" and all(self.type_of(a).base == "float" for a in e.args):
            return f"rt.np_fmin(rt.np_fmax({args[0]}, {args[1]}), {args[2]})"  # as Runtime.clamp
        method = RUNTIME_NAMES.get(name, name)
        from ..runtime import Runtime

        if not IDENT.match(method) or not hasattr(Runtime, method):
            raise _error(f"the built-in {name}() is not supported by the NumPy backend", e)
        if name in DERIVATIVES:
            args.append("S.width")
        return f"rt.{method}({', '.join(args)})"

    def pow_rewrite(self, e: A.Call, args: list[str]) -> str | None:
        """Mesa's compile-time rewrites of `pow` (see `Runtime.pow_const`): a constant exponent
        with a component of 1.0, 2.0, 4.0 or +0.0 becomes products (`rt.pow_const`), a constant
        base of all ones becomes 1 (`rt.pow_one`), a constant base of all twos becomes `exp2`
        (nir_opt_algebraic's `fpow(2.0, a) -> fexp2(a)`: the same bits as the run-time formula,
        whose log2(2.0) is exactly 1, without the log2); None: the run-time `rt.pow`."""
        base = self.model.const_value(e.args[0])
        if base is not None and all(v == 1.0 for v in _components(base)):
            return f"rt.pow_one({args[1]})"
        if base is not None and all(v == 2.0 for v in _components(base)):
            return f"rt.exp2({args[1]})"
        c = self.model.const_value(e.args[1])
        if c is None:
            return None
        comps = [float(v) for v in _components(c)]
        if not any(v in (1.0, 2.0, 4.0) or (v == 0.0 and str(v) == "0.0") for v in comps):
            return None
        lit = (
            repr(comps[0]) if not isinstance(c, tuple) else "(" + ", ".join(map(repr, comps)) + ")"
        )
        return f"rt.pow_const({args[0]}, {lit})"

    # -- l-values ------------------------------------------------------------------------------
    def lvalue(self, e: Any, mask: str | None) -> LValue:
        """The l-value a write (assignment, ++/--, out argument) writes: `e` is the whole target."""
        lv = self.lvalue_path(e, mask)
        uni = self.fn.uni if self.fn is not None else None
        lv.free = uni is not None and uni.is_free(e)
        return lv

    def lvalue_path(self, e: Any, mask: str | None) -> LValue:
        if isinstance(e, A.Identifier):
            sym = self.model.symbol_of(e)
            assert sym is not None  # every name of a checked program has its symbol
            return LValue(self.var_name(sym, e), sym.type)
        if isinstance(e, A.Field):
            lv = self.lvalue_path(e.base, mask)
            bt = self.type_of(e.base)
            if bt.is_struct:
                lv.path.append(("field", self.member(e.name, e)))
            else:
                idx = self.model.swizzle_indices(e)
                if bt.is_scalar:
                    return lv
                if lv.path and lv.path[-1][0] == "swz":
                    prev = lv.path.pop()[1]
                    idx = tuple(prev[i] for i in idx)
                lv.path.append(("swz", tuple(idx)))
            return lv
        if isinstance(e, A.Index):
            lv = self.lvalue_path(e.base, mask)
            cv = self.model.const_value(e.index)
            if isinstance(cv, int) and not isinstance(cv, bool):
                index = str(cv)
            else:
                index = self.tmp(self.expr(e.index, mask))
            lv.path.append(("index", index))
            return lv
        raise _error("this expression cannot be assigned to", e)

    def read(self, lv: LValue, upto: int | None = None) -> str:
        v = lv.base
        for item in lv.path[:upto]:
            kind, arg = item
            if kind == "field":
                v = f'rt.field({v}, "{arg}")'
            elif kind == "swz":
                v = (
                    f"{v}[{arg[0]}]"
                    if len(arg) == 1
                    else f'rt.swizzle({v}, "{"".join("xyzw"[i] for i in arg)}")'
                )
            else:
                v = f"rt.index({v}, {arg})"
        return v

    def write(self, lv: LValue, value: str, mask: str | None) -> None:
        new = value
        m = None if lv.free else mask
        for k in range(len(lv.path) - 1, -1, -1):
            parent = self.read(lv, k)
            kind, arg = lv.path[k]
            if kind == "field":
                new = f'rt.assign_field({parent}, "{arg}", {new}, {m})'
            elif kind == "swz":
                new = (
                    f'rt.assign_swizzle({parent}, "{"".join("xyzw"[i] for i in arg)}", {new}, {m})'
                )
            else:
                new = f"rt.assign_index({parent}, {arg}, {new}, {m})"
            m = None
        if lv.path:
            self.emit(f"{lv.base} = {new}")
        else:
            self.assign_stmt(lv.base, new, m)
