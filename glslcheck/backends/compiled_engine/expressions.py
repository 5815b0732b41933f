"""The expression half of the per-pixel code generator: GLSL expressions, l-values, writes and
calls as Python expressions over scalar leaves (values.py's `Val`).

`ExpressionEmitter` is Codegen's base class (codegen.py): its methods use Codegen's emission
(`emit`, `tmp`, `fresh`), constants (`cf`, `ci`), variables (`var_parts`) and functions
(`variant_name`, `needs`); the statements and the module are Codegen's own."""

from __future__ import annotations

from typing import Any

from ...base.precision import float32_literal
from ...frontend import syntax as A
from ...language import glsl_types as T
from ...semantics.consteval import f32
from ...semantics.model import Constructor, Symbol
from ..cpu_core import nir_fold
from ..cpu_core.common import sum_in_order
from ..cpu_core.inline import bound_code, inline_call, worth_inlining
from .builtin_calls import builtin_call
from .constant_globals import load_time_parts
from .ray_dots import ray_call_args
from .sum_chains import SumChains, nir_chain_params
from .values import (
    CAST,
    DTYPE,
    PURE_LINE,
    SPECULATE_LINES,
    Arr,
    Dyn,
    Val,
    broadcast_const,
    engine_error,
    flatten,
    leaves,
    may_change,
    not_yet,
    pure_expr,
)

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ...semantics.model import Model
    from ..cpu_core.facts import Facts
    from .fold_values import FoldValues


class FnState:
    """The function Codegen is generating."""

    def __init__(self, sym: Symbol | None, uni: Any = None) -> None:
        self.sym = sym
        self.uni = uni  # cpu_core's Uniformity of the function (None: global initializers)
        self.outs: list = []  # the parts of out/inout parameters, returned after the value
        self.loops: list[tuple[str, Any]] = []  # (kind, continue emitter)
        self.sum_chains: dict[tuple, tuple[list, int]] = {}  # a chain -> its base, its depth
        self.sum_index: dict[int, str] = {}  # unrolled loop -> its pass count's name
        self.ray_roots: dict[int, tuple[str, int]] = {}  # ray root -> its rsq's name, depth
        self.terms: dict[int, list] = {}  # a write of a returned sum's term -> its kept parts
        self.call_k: dict[int, list] = {}  # a call -> the constant sunk into its result


class ExpressionEmitter(SumChains):
    """Expressions, l-values and calls of Codegen (see the module docstring)."""

    if TYPE_CHECKING:  # Codegen's (codegen.py), declared for type checkers
        model: Model
        facts: Facts
        path: str
        fma: bool
        float_to_uint: str
        entry: Any
        lines: list[str]
        indent: int
        fn: FnState | None
        needs: dict[str, list[str]]
        variants: set[tuple[int, frozenset]]
        pending: list[tuple[Any, frozenset]]
        derivative: Any
        samples: bool

        def fold_context(self) -> FoldValues: ...
        def emit(self, text: str) -> None: ...
        def fresh(self, prefix: str = "t") -> str: ...
        def tmp(self, value: str) -> str: ...
        def tmp_fresh(self, value: str) -> str: ...
        def atom(self, value: Any) -> Any: ...
        def cf(self, v: float) -> str: ...
        def ci(self, v: int, unsigned: bool = False) -> str: ...
        def var_parts(self, sym: Symbol, node: Any) -> list: ...
        def fn_name(self, sym: Symbol) -> str: ...
        def variant_name(self, sym: Symbol, seed: frozenset) -> str: ...
        def discard_flag(self) -> str: ...
        def kept_register(self, e: A.Call, fn: Symbol, value: list) -> list: ...
        def leave_discarded(self, node: Any) -> None: ...

    # -- writes --------------------------------------------------------------------------------
    def write(self, targets: list, values: list, fresh_arrays: bool = False) -> None:
        """Assign value parts to target parts, in order. Values that read a target are copied
        first when several parts are written (`v.xy = v.yx`)."""
        if len(targets) > 1:
            values = [
                self.tmp_copy(v)
                if isinstance(v, str)
                and not v.startswith(("F_", "I_", "U_", "_t"))
                and v not in ("True", "False")
                else v
                for v in values
            ]
        for t, v in zip(targets, values):
            if isinstance(t, Arr):
                src = v.whole() if isinstance(v, Arr) else v
                if fresh_arrays and t.name.startswith("a_"):
                    self.emit(f"{t.name} = acopy({src})")
                else:
                    self.emit(f"aset({t.name}, {t.off}, {src})")
            elif isinstance(t, Dyn):
                # Every element takes the value where the index is its own, itself elsewhere:
                # one select each (lanes_rt.lsel), no branch (see read()).
                v = self.tmp(v)
                for k, p in enumerate(t.parts):
                    self.write([p], [f"lsel({t.idx} == {k}, {v}, {self.read(p)})"])
            else:
                self.emit(f"{t} = {v}")

    def read(self, p: Any) -> Any:
        """A target part as a value part (a run-time index becomes a chain of selects).

        lanes_rt.lsel, not Python's `a if c else b`: the parts are names and constants, so
        computing all of them costs nothing, and a conditional expression is two basic blocks
        in numba's IR. `lights[i].pos` in a lights loop read 4 x 3 leaves that way, 600 of
        the 711 blocks of a Lab 4 submission's shading function (10-lab4 of the real corpus);
        numba's liveness and SSA passes grow with blocks x variables, and its lockstep module
        (8 lanes, 5,627 blocks) took 341 s and 9.2 GB to compile."""
        if isinstance(p, Dyn):
            parts = [self.read(q) for q in p.parts]
            text = parts[-1]
            for k in range(len(parts) - 2, -1, -1):
                text = f"lsel({p.idx} == {k}, {parts[k]}, {text})"
            return self.tmp(text)
        return p

    def lvalue(self, e: Any) -> list:
        """The target parts of an l-value, its index expressions evaluated (once, in order)."""
        if isinstance(e, A.Identifier):
            sym = self.model.symbol_of(e)
            assert sym is not None  # every name of a checked program has its symbol
            return list(self.var_parts(sym, e))
        if isinstance(e, A.Field):
            base = self.lvalue(e.base)
            return self.select_field(self.type_of(e.base), base, e)
        if isinstance(e, A.Index):
            base = self.lvalue(e.base)
            return self.select_index(self.type_of(e.base), base, e)
        raise engine_error("this expression cannot be assigned to", e)

    def select_field(self, bt: Any, parts: list, e: A.Field) -> list:
        if bt.is_struct:
            k = 0
            for fname, ft in bt.fields:
                n = len(leaves(ft, e))
                if fname == e.name:
                    return parts[k : k + n]
                k += n
            raise engine_error(f"no field '{e.name}'", e)
        idx = self.model.swizzle_indices(e)
        if bt.is_scalar:
            return [parts[0]] * len(idx)
        return [parts[i] for i in idx]

    def select_index(self, bt: Any, parts: list, e: A.Index) -> list:
        cv = self.model.const_value(e.index)
        const = isinstance(cv, int) and not isinstance(cv, bool)
        if bt.is_array:
            n = bt.array_size
            if const:
                i = str(min(max(cv, 0), n - 1))
            else:
                i = self.tmp(f"index({self.expr(e.index).parts[0]}, {n})")
            if any(isinstance(p, Arr) for p in parts):
                return [p.at(i) if isinstance(p, Arr) else self.bad_array(e) for p in parts]
            m = len(parts) // n  # scalars, leaf by leaf: leaf j of element k is parts[j * n + k]
            if const:
                return [parts[j * n + int(i)] for j in range(m)]
            return [Dyn(i, parts[j * n : (j + 1) * n]) for j in range(m)]
        if bt.is_vector:
            if const:
                return [parts[min(max(cv, 0), bt.size - 1)]]
            i = self.tmp(f"index({self.expr(e.index).parts[0]}, {bt.size})")
            return [Dyn(i, list(parts))]
        if bt.is_matrix:
            r = bt.rows
            if const:
                c = min(max(cv, 0), bt.cols - 1)
                return parts[c * r : (c + 1) * r]
            i = self.tmp(f"index({self.expr(e.index).parts[0]}, {bt.cols})")
            return [Dyn(i, [parts[c * r + row] for c in range(bt.cols)]) for row in range(r)]
        raise engine_error("this value cannot be indexed", e)

    def bad_array(self, e: Any) -> str:
        raise not_yet("this array access", e)

    # -- expressions ---------------------------------------------------------------------------
    def type_of(self, e: Any) -> Any:
        return self.model.type_of(e)

    def expr(self, e: Any) -> Val:
        method = getattr(self, "_expr_" + type(e).__name__, None)
        if method is None:
            raise not_yet(f"{type(e).__name__} expressions", e)
        v = method(e)
        cv = self.model.const_value(e)
        if (
            cv is not None
            and v.const is None
            and not self.type_of(e).is_array
            and not self.type_of(e).is_struct
        ):
            v.const = flatten(cv)
        v.uni = self.lane_uniform(e)
        if self.fn is not None and self.fn.sym is not None and self.facts.order.needs_temp(e):
            # Mesa computes e here, before a later part of the statement writes what it reads
            # (cpu_core/eval_order.py): a variable's name is copied too, as it may be rebound
            v.parts = [self.tmp_fresh(p) if may_change(p) else p for p in v.parts]
        # long expressions go to temporaries (Python's parser nests 200 brackets at most)
        v.parts = [self.tmp(p) if isinstance(p, str) and len(p) > 300 else p for p in v.parts]
        return v

    def lane_uniform(self, e: Any) -> bool:
        """Whether the NumPy backend holds e's value as one lane for the whole tile and takes it
        for a compile-time constant (Runtime._const: a lane-uniform value that is not a uniform
        input): Mesa's constant folding, approximated there (Runtime.fmul). By numpy_backend's
        own analysis (Uniformity); global initializers run on one lane there."""
        node = e
        while isinstance(node, (A.Field, A.Index)) and not (
            isinstance(node, A.Field)
            and self.model.is_swizzle(node)
            and len(self.model.swizzle_indices(node)) > 1
        ):
            node = node.base
        if isinstance(node, A.Field) and self.model.is_swizzle(node):
            idx = tuple(self.model.swizzle_indices(node))
            inner = node.base
            if (
                isinstance(inner, A.Identifier)
                and self._is_input(inner)
                and (
                    idx == tuple(range(len(idx)))
                    or (
                        len(idx) > 1
                        and idx[1] - idx[0] > 0
                        and all(b - a == idx[1] - idx[0] for a, b in zip(idx, idx[1:]))
                    )
                )
            ):
                return False  # a view of a read-only uniform (Runtime.swizzle)
        elif isinstance(node, A.Identifier) and self._is_input(node):
            return False
        if self.fn is None or self.fn.uni is None:
            return True
        return self.fn.uni.is_uniform(e)

    def one_lane(self, e: Any) -> bool:
        """Whether the NumPy backend holds e's value as one lane for the whole tile (a uniform
        input too: Uniformity's verdict; global initializers run on one lane there)."""
        return self.fn is None or self.fn.uni is None or self.fn.uni.is_uniform(e)

    def _is_input(self, ident: Any) -> bool:
        sym = self.model.symbol_of(ident)
        return sym is not None and (
            sym.kind == "uniform"
            or (sym.kind == "global" and sym.qualifier == "uniform")
            or (sym.kind == "builtin-var" and sym.name == "gl_FragCoord")
        )

    def _expr_IntLiteral(self, e: A.IntLiteral) -> Val:
        t = self.type_of(e)
        return Val(t, [self.ci(e.value, e.unsigned or t == T.UINT)], [e.value])

    def _expr_FloatLiteral(self, e: A.FloatLiteral) -> Val:
        v = e.value
        if e.text and float32_literal(e.text) != f32(
            v
        ):  # a decimal just off a float32 halfway point
            v = float32_literal(e.text)  # rounded to float32 once, not through float64
        return Val(T.FLOAT, [self.cf(v)], [v])

    def _expr_BoolLiteral(self, e: A.BoolLiteral) -> Val:
        return Val(T.BOOL, ["True" if e.value else "False"], [e.value])

    def _expr_Identifier(self, e: A.Identifier) -> Val:
        sym = self.model.symbol_of(e)
        if sym is None:
            raise engine_error(f"'{e.name}' has no symbol", e)
        if self.inlining():
            bound = bound_code(self.fold_context(), sym)  # a parameter of an inlined call
            if bound is not None:
                return Val(bound.t, list(bound.parts), bound.const, bound.uni, bound.one)
        return Val(sym.type, [self.read(p) for p in self.var_parts(sym, e)])

    def inlining(self) -> bool:
        """A call is being inlined (nir_fold's cpu_core/inline.py: Mesa's rewrites reach into
        its argument)."""
        fold = self.fold_context() if self.fn is not None and self.fn.sym is not None else None
        return fold is not None and bool(fold.fold_state.inline_frames)

    def _expr_Field(self, e: A.Field) -> Val:
        base = self.expr(e.base)
        return Val(self.type_of(e), self.select_field(base.t, base.parts, e))

    def _expr_Index(self, e: A.Index) -> Val:
        bt = self.type_of(e.base)
        base = self.expr(e.base)
        parts = self.select_index(
            bt, [p if isinstance(p, Arr) else self.atom(p) for p in base.parts], e
        )
        return Val(self.type_of(e), [self.read(p) for p in parts])

    def _expr_MethodCall(self, e: A.MethodCall) -> Val:
        bt = self.type_of(e.base)
        if e.name == "length":
            n = (
                bt.array_size
                if bt.is_array
                else bt.size
                if bt.is_vector
                else bt.cols
                if bt.is_matrix
                else None
            )
            if n is not None:
                return Val(T.INT, [self.ci(n)], [n])
        raise not_yet(f"the method '.{e.name}()'", e)

    def _expr_Sequence(self, e: A.Sequence) -> Val:
        for x in e.exprs[:-1]:
            self.expr(x)
        return self.expr(e.exprs[-1])

    def _expr_Assignment(self, e: A.Assignment) -> Val:
        targets = self.lvalue(e.target)
        tt = self.type_of(e.target)
        merged = self.component_write(e, Val(tt, [self.read(p) for p in targets]))
        value = merged if merged is not None else self.expr(e.value)
        if merged is None:
            merged = self.repeated_sum(e, targets)
        if merged is not None:
            value = merged
        else:
            value = self.keep_term(e, value)
        if merged is None and e.op != "=":
            old = Val(tt, [self.read(p) for p in targets])
            value = self.binary_values(e.op[:-1], old, value, e)
        parts = [self.tmp(p) if isinstance(p, str) else p for p in value.parts]
        self.write(targets, parts)
        return Val(tt, parts)

    def component_write(self, node: Any, old: Val | None = None) -> Val | None:
        """The value a write gives a local as NIR sees it per component (nir_fold.component_write
        decides and computes it: constants merged through component writes, a ``+= e`` undone
        by a later ``-= e``; first, nir_fold.compound_copies: ``x op= #k`` merged in a copy of
        an unrolled loop), or None: the write as usual. ``old``: the target's value before an
        assignment."""
        if self.fn is None or self.fn.sym is None:
            return None
        if any(not isinstance(p, str) for p in (old.parts if old is not None else [])):
            return None

        ctx = self.fold_context()
        merged = nir_fold.compound_copies(ctx, node, None, old) if old is not None else None
        return merged if merged is not None else nir_fold.component_write(ctx, node, None, old)

    def _expr_Unary(self, e: A.Unary) -> Val:
        if e.op in ("++", "--"):
            return self.incdec(e, post=False)
        v = self.expr(e.operand)
        t = v.t
        if e.op == "+":
            return v
        if e.op == "-":
            if t.base == "float":
                return Val(t, [f"(-{p})" for p in v.parts])
            return Val(t, [f"{CAST[t.base]}(-np.int64({p}))" for p in v.parts])
        if e.op == "!":
            return Val(t, [f"(not {v.parts[0]})"])
        if e.op == "~":
            return Val(t, [f"{CAST[t.base]}(~{p})" for p in v.parts])
        raise not_yet(f"the operator '{e.op}'", e)

    def _expr_Postfix(self, e: A.Postfix) -> Val:
        return self.incdec(e, post=True)

    def incdec(self, e: Any, post: bool) -> Val:
        targets = self.lvalue(e.operand)
        t = self.type_of(e.operand)
        old = [self.tmp(self.read(p)) if post else self.read(p) for p in targets]
        if post:
            old = [self.tmp_copy(p) for p in old]
        one = self.cf(1.0) if t.base == "float" else self.ci(1, t.base == "uint")
        op = "+" if e.op == "++" else "-"
        if t.base == "float":
            new = [self.tmp(f"({p} {op} {one})") for p in old]
        else:
            new = [self.tmp(f"{CAST[t.base]}({p} {op} {one})") for p in old]
        self.write(targets, new)
        return Val(t, old if post else new)

    def tmp_copy(self, p: str) -> str:
        t = self.fresh()
        self.emit(f"{t} = {p}")
        return t

    def _expr_Ternary(self, e: A.Ternary) -> Val:
        t = self.type_of(e)
        c = self.tmp(self.expr(e.cond).parts[0])
        n = len(leaves(t, e))
        mark = len(self.lines)
        a = self.expr(e.then).parts
        if self._speculable(mark, a):
            then_end = len(self.lines)
            b = self.expr(e.else_).parts
            if self._speculable(then_end, b):
                # Both sides are a few selects, compares and arithmetic of names and
                # constants: computed both, one select each (lanes_rt.lsel), no branch.
                # Computing the side not taken does nothing and cannot fail (IEEE float
                # math, error_model="numpy"); as if/else each leaf would be two basic blocks
                # per pixel and a masked write per lane in lockstep (h38-2d-sprites: 524
                # ternaries, `idx = y == 14.0 ? (x <= 7.0 ? 40960.0 : 42.0) : idx`).
                return Val(t, [self.tmp(f"lsel({c}, {x}, {y})") for x, y in zip(a, b)])
            del self.lines[then_end:]  # the else side's statements: written again in its branch
        res = [self.fresh() for _ in range(n)]
        # the then side's statements (if any) run only where c holds
        body = self.lines[mark:]
        del self.lines[mark:]
        self.emit(f"if {c}:")
        self.indent += 1
        self.lines += ["    " + line for line in body]
        self.assign_fresh(res, a)
        self.indent -= 1
        self.emit("else:")
        self.indent += 1
        b = self.expr(e.else_).parts
        self.assign_fresh(res, b)
        self.indent -= 1
        out = [Arr(r, 0, p.size, p.base) if isinstance(p, Arr) else r for r, p in zip(res, a)]
        return Val(t, out)

    def _speculable(self, mark: int, parts: list) -> bool:
        """The lines written since mark and the value parts are pure and cheap: at most a few
        assignments of temporaries, each of names, literals, operators and lsel."""
        if any(not isinstance(p, str) or not pure_expr(p) for p in parts):
            return False
        body = self.lines[mark:]
        if len(body) > SPECULATE_LINES:
            return False
        pad = "    " * self.indent
        for line in body:
            m = PURE_LINE.match(line)
            if m is None or m.group(1) != pad or not pure_expr(m.group(2)):
                return False
        return True

    def assign_fresh(self, names: list[str], parts: list) -> None:
        for r, p in zip(names, parts):
            self.emit(f"{r} = acopy({p.whole()})" if isinstance(p, Arr) else f"{r} = {p}")

    def _expr_Binary(self, e: A.Binary) -> Val:
        op = e.op
        if op in ("&&", "||"):
            lcode = self.tmp(self.expr(e.left).parts[0])
            mark = len(self.lines)
            self.indent += 1
            rcode = self.expr(e.right).parts[0]
            self.indent -= 1
            if len(self.lines) == mark:  # nothing to run first: Python's own short circuit
                return Val(T.BOOL, [f"({lcode} {'and' if op == '&&' else 'or'} {rcode})"])
            res = self.fresh()
            body = self.lines[mark:]
            del self.lines[mark:]
            self.emit(f"{res} = {lcode}")
            self.emit(f"if {'' if op == '&&' else 'not '}{res}:")
            self.lines += body
            self.emit(f"    {res} = {rcode}")
            return Val(T.BOOL, [res])
        if op in ("+", "-", "*", "/") and self.samples:  # float16 on lowp lookups
            from .texture_calls import lowp_tree

            low = lowp_tree(self, e)
            if low is not None:
                return low
        if self.fn is not None and self.fn.sym is not None:
            from .fold_values import COPIED, fused_sum

            if self.fold_context().has_effects(e):  # a constant sunk into a call's result
                folded = self.sunk_into_call(e)
                if folded is not None:
                    return folded
            elif op == "+":  # (factoring never applies: x is no product to NIR)
                folded = fused_sum(self, e)  # ffma fused and split after a folded call
                if folded is not None:
                    return folded
            folded = nir_fold.rewrite_binary(self.fold_context(), e, None, COPIED)  # Mesa's order
            if folded is not None:
                return folded
        left = self.expr(e.left)
        right = self.expr(e.right)
        if (
            op == "%"
            and left.const is not None
            and right.const is not None
            and left.t.base == "int"
        ):
            return self.componentwise(
                left, right, self.type_of(e), lambda a, b, i: f"irem_const({a}, {b})"
            )
        return self.binary_values(op, left, right, e)

    def binary_values(self, op: str, left: Val, right: Val, e: Any) -> Val:
        lt, rt_ = left.t, right.t
        rtype = self.type_of(e) if not isinstance(e, A.Assignment) else lt
        if op == "*" and (lt.is_matrix or rt_.is_matrix) and not (lt.is_scalar or rt_.is_scalar):
            return self.linear_product(left, right, rtype)
        if op in ("==", "!="):
            pairs = []
            for a, b, base in zip(left.parts, right.parts, [x for x, _ in leaves(lt, e)]):
                if isinstance(a, Arr):
                    pairs.append(f"np.array_equal({a.whole()}, {b.whole()})")
                else:
                    pairs.append(f"({a} == {b})")
            text = " and ".join(pairs) if len(pairs) > 1 else pairs[0]
            text = f"({text})"
            return Val(T.BOOL, [text if op == "==" else f"(not {text})"])
        if op == "^^":
            return Val(T.BOOL, [f"({left.parts[0]} != {right.parts[0]})"])
        base = lt.base
        if base == "float":
            if op == "*":
                return self.fmul(left, right, rtype)
            if op in ("+", "-"):
                return self.fadd(op, left, right, rtype, e)
            if op in ("/", "<", "<=", ">", ">="):
                return self.componentwise(left, right, rtype, lambda a, b, i: f"({a} {op} {b})")
        elif base in ("int", "uint"):
            cast = CAST[base]
            u = base == "uint"
            if op in ("+", "-", "*"):
                return self.componentwise(
                    left, right, rtype, lambda a, b, i: f"{cast}({a} {op} {b})"
                )
            if op in ("<", "<=", ">", ">="):
                return self.componentwise(left, right, rtype, lambda a, b, i: f"({a} {op} {b})")
            if op in ("&", "|", "^"):
                return self.componentwise(
                    left, right, rtype, lambda a, b, i: f"{cast}({a} {op} {b})"
                )
            fn = {
                "/": "udiv" if u else "idiv",
                "%": "urem" if u else "irem",
                "<<": "ushl" if u else "ishl",
                ">>": "ushr" if u else "ishr",
            }.get(op)
            if fn is not None:
                return self.componentwise(left, right, rtype, lambda a, b, i: f"{fn}({a}, {b})")
        raise not_yet(f"the operator '{op}' on '{lt}'", e)

    def componentwise(self, left: Val, right: Val, rtype: Any, fn) -> Val:
        n = max(len(left.parts), len(right.parts))
        a = left.parts if len(left.parts) == n else [self.atom(left.parts[0])] * n
        b = right.parts if len(right.parts) == n else [self.atom(right.parts[0])] * n
        return Val(rtype, [fn(x, y, i) for i, (x, y) in enumerate(zip(a, b))])

    def fmul(self, left: Val, right: Val, rtype: Any) -> Val:
        """Float `*` as Runtime.fmul: a compile-time constant zero component times a value that
        is not a constant is 0 (NIR folds x * 0.0), also for NaN and Inf; a subnormal product
        of two values that are not constants is a zero of its sign (llvmpipe's FTZ)."""
        n = max(len(left.parts), len(right.parts))
        if left.constlike == right.constlike:
            ftz = "daz" if not left.constlike else ""
            return self.componentwise(left, right, rtype, lambda a, b, i: f"{ftz}({a} * {b})")
        zv = left if left.constlike else right
        zc = broadcast_const(zv.const, n)
        zero = self.cf(0.0)
        zparts = zv.parts if len(zv.parts) == n else [self.atom(zv.parts[0])] * n
        if zc is None:
            zparts = [self.atom(p) for p in zparts]
            if zv is left:
                left = Val(left.t, zparts)
            else:
                right = Val(right.t, zparts)

        def one(a: str, b: str, i: int) -> str:
            if zc is not None:
                return zero if zc[i] == 0 else f"({a} * {b})"
            return f"({zero} if {zparts[i]} == {zero} else ({a} * {b}))"

        return self.componentwise(left, right, rtype, one)

    def fadd(self, op: str, left: Val, right: Val, rtype: Any, e: Any = None) -> Val:
        """Float `+`/`-` as Runtime.fadd/fsub: a compile-time constant zero added to (or
        subtracted from) a value that is not a constant leaves that value, its sign kept."""
        n = max(len(left.parts), len(right.parts))
        if left.constlike == right.constlike or not self.zero_add(e):
            return self.componentwise(left, right, rtype, lambda a, b, i: f"({a} {op} {b})")
        zleft = left.constlike  # the operand that may be a constant zero: the left one?
        zc = broadcast_const((left if zleft else right).const, n)
        zero = self.cf(0.0)
        if zc is None:  # (the operands are read twice below: once, in temporaries; a known
            # zero reads each once, so the text stays lazy, read where Mesa reads it, after
            # a later call of the statement: cpu_core/eval_order.py)
            left = Val(left.t, [self.atom(p) for p in left.parts], left.const, left.uni)
            right = Val(right.t, [self.atom(p) for p in right.parts], right.const, right.uni)

        def one(a: str, b: str, i: int) -> str:
            z = a if zleft else b
            kept = (b if op == "+" else f"(-{b})") if zleft else a
            if zc is not None:
                return kept if zc[i] == 0 else f"({a} {op} {b})"
            return f"({kept} if {z} == {zero} else ({a} {op} {b}))"

        return self.componentwise(left, right, rtype, one)

    def zero_add(self, e: Any) -> bool:
        """Whether the NumPy backend tests this `+`/`-` for a constant zero operand (nir_fold.
        zero_add: Mesa drops an added constant zero, keeping the sign of a -0.0)."""
        if e is None:
            return True
        if self.fn is None or self.fn.sym is None or not isinstance(e, A.Binary):
            return self.fn is None or self.fn.sym is None

        return nir_fold.zero_add(self.fold_context(), e)

    def linear_product(self, left: Val, right: Val, rtype: Any) -> Val:
        lt, rt_ = left.t, right.t
        a = [self.atom(p) for p in left.parts]
        b = [self.atom(p) for p in right.parts]
        if lt.is_matrix and rt_.is_vector:  # sum of m[c] * v[c] in c order
            return Val(rtype, self.mat_vec(a, lt.cols, lt.rows, b))
        if lt.is_vector and rt_.is_matrix:  # component c: dot(v, m[c])
            r = rt_.rows
            return Val(rtype, [self.dot_text(a, b[c * r : (c + 1) * r]) for c in range(rt_.cols)])
        out = []
        k = lt.cols
        for c in range(rt_.cols):
            out += [self.atom(p) for p in self.mat_vec(a, k, lt.rows, b[c * k : (c + 1) * k])]
        return Val(rtype, out)

    def mat_vec(self, m: list, cols: int, rows: int, v: list) -> list:
        out = []
        for r in range(rows):
            s = f"({m[r]} * {v[0]})"
            for c in range(1, cols):
                s = f"({s} + ({m[c * rows + r]} * {v[c]}))"
            out.append(s)
        return out

    def dot_text(self, a: list, b: list, ca: list | None = None, cb: list | None = None) -> str:
        """Sum of products right to left (Runtime.dot); with exactly one constant operand, a
        product with a constant zero is 0."""
        n = len(a)
        fold = (ca is None) != (cb is None)
        prods = []
        for i in range(n):
            if fold and ((ca is not None and ca[i] == 0) or (cb is not None and cb[i] == 0)):
                prods.append(self.cf(0.0))
            else:
                prods.append(f"({a[i]} * {b[i]})")
        s = prods[-1]
        for i in range(n - 2, -1, -1):
            s = f"({prods[i]} + {s})"
        return s

    # -- calls ---------------------------------------------------------------------------------
    def _expr_Call(self, e: A.Call) -> Val:
        tgt = self.model.call_target(e)
        if isinstance(tgt, Constructor):
            return self.constructor(e, tgt.type)
        if isinstance(tgt, Symbol):
            return self.user_call(e, tgt)
        if tgt is None:
            raise engine_error(f"the call of '{e.callee}' was not resolved by the checker", e)
        return builtin_call(self, e, tgt)

    def sunk_chain(self, fn: Symbol) -> list | None:
        """nir_fold.sunk_return of user function `fn`: the ``+=`` chain it returns, into which a
        caller's constant sinks (the function then takes a flag `_kf` and the constant's parts
        `_k0..`), else None."""

        return nir_fold.sunk_return(self.fold_context(), fn)

    def keep_term(self, node: Any, value: Val) -> Val:
        """value, in temporaries where `node` writes a term of this function's returned sum
        (nir_fold.sunk_return; the NumPy backend's keep_term): its return adds the terms in
        NIR's order."""
        fs = self.fn
        if fs is None or fs.sym is None:
            return value
        chain = self.sunk_chain(fs.sym)
        if chain is None or not any(w is node for w, _, _ in chain):
            return value
        parts = [self.tmp_fresh(p) for p in value.parts]
        fs.terms[id(node)] = parts
        return Val(value.t, parts, value.const, value.uni, value.one)

    def sunk_return(self, parts: list) -> list:
        """The returned parts of a function with a returned sum (nir_fold.sunk_order; the NumPy
        backend's sunk_return_value): with the caller's constant sunk into the terms where
        `_kf`, else as written."""
        fs = self.fn
        if fs is None or fs.sym is None:
            return parts
        chain = self.sunk_chain(fs.sym)
        if chain is None or not all(id(w) in fs.terms for w, _, _ in chain):
            return parts

        order = nir_fold.sunk_order(self.fold_context(), chain)
        out = []
        for j, p in enumerate(parts):
            sunk = sum_in_order(order, [fs.terms[id(w)][j] for w, _, _ in chain], f"_k{j}")
            out.append(self.tmp(f"({sunk} if _kf else {p})"))
        return out

    def sunk_into_call(self, e: A.Binary) -> Val | None:
        """``f(...) +- #c`` where the constant sinks into f's returned sum (nir_fold.sunk_call):
        the call, passed the constant, else None."""

        sunk = nir_fold.sunk_call(self.fold_context(), e)
        if sunk is None:
            return None
        call, k, negative = sunk
        kv = self.expr(k)
        assert self.fn is not None and kv.const is not None  # (a constant, in a function)
        self.fn.call_k[id(call)] = [self.cf(f32(-c if negative else c)) for c in kv.const]
        return self.expr(call)

    def sunk_args(self, e: A.Call, fn: Symbol) -> list[str]:
        """The flag and constant of a call of a function with a returned sum (:meth:`sunk_chain`):
        the constant a caller's sum sinks into it, else a false flag and zeros; [] otherwise."""
        if self.sunk_chain(fn) is None:
            return []
        k = self.fn.call_k.get(id(e)) if self.fn is not None else None
        if k is not None:
            return ["True", *k]
        return ["False"] + [self.cf(0.0)] * len(leaves(fn.type, e))

    def user_call(self, e: A.Call, fn: Symbol) -> Val:
        if self.fn is not None and self.fn.sym is not None:
            if worth_inlining(self.fold_context(), e, fn, nir_fold.dot_operand):
                return inline_call(self.fold_context(), e, fn, None)  # as the NumPy backend
            from .fold_values import folded_call

            folded = folded_call(self, e, fn)  # constants propagated into the call
            if folded is not None:
                return folded
            once = load_time_parts(self, e, fn)  # the same in every pixel: at load, or a frame
            if once is not None:
                return Val(fn.type, once)
        args: list[str] = []
        outs: list[list] = []
        chained = nir_chain_params(self, fn)
        inouts: dict[int, str] = {}
        for i, (a, (_, ptype, d)) in enumerate(zip(e.args, fn.params)):
            if d == "in":
                parts = self.expr(a).parts
            else:
                targets = self.lvalue(a)
                outs.append(targets)
                parts = [self.read(p) for p in targets] if d == "inout" else []
                if i in chained:  # (the value before the call, a chain's base: kept)
                    parts = [self.tmp_copy(p) for p in parts]
                    inouts[i] = parts[0]
            for p in parts:
                args.append(p.whole() if isinstance(p, Arr) else p)
        if self.fn is not None and self.fn.sym is not None:
            for key, g in nir_fold.chain_globals(self.fold_context(), fn):  # (globals' chains)
                inouts[key] = self.tmp_copy(self.read(self.var_parts(g, e)[0]))
        args += self.chain_args(e, fn, inouts) + self.sunk_args(e, fn)
        if self.fn is not None and self.fn.sym is not None:
            args += ray_call_args(self, e, fn)  # a ray's constants (nir_fold.ray_dots)
        rtype = fn.type
        n_val = 0 if rtype.is_void else len(leaves(rtype, e))
        ret_leaves = [] if rtype.is_void else leaves(rtype, e)
        out_leaves = [leaf for (_, pt, d) in fn.params if d != "in" for leaf in leaves(pt, e)]
        res = [self.fresh() for _ in range(n_val + len(out_leaves))]
        seed = frozenset(
            i
            for i, (a, (_, _, d)) in enumerate(zip(e.args, fn.params))
            if d != "out" and self.lane_uniform(a)
        )
        if seed and (id(fn), seed) not in self.variants:
            self.variants.add((id(fn), seed))
            self.pending.append((fn, seed))
        call = f"{self.variant_name(fn, seed)}({', '.join(self.needs[self.fn_name(fn)] + args)})"
        if res:
            self.emit(f"{', '.join(res)}, = {call}")
        else:
            self.emit(call)
        if id(fn) in self.facts.may_discard:
            self.emit(f"if {self.discard_flag()}:")
            self.indent += 1
            self.leave_discarded(e)
            self.indent -= 1
        k = n_val
        for targets in outs:
            vals = []
            for _ in targets:
                base, size = out_leaves[k - n_val]
                vals.append(Arr(res[k], 0, size, base) if size is not None else res[k])
                k += 1
            self.write(targets, vals)
        value = [
            Arr(r, 0, n, b) if n is not None else r for r, (b, n) in zip(res[:n_val], ret_leaves)
        ]
        return Val(rtype, self.kept_register(e, fn, value))

    def constructor(self, e: A.Call, t: Any) -> Val:
        args = [self.expr(a) for a in e.args]
        if t.is_array and all(size is None for _, size in leaves(t, e)):
            m = len(leaves(t.element, e))
            return Val(t, [self.atom(v.parts[j]) for j in range(m) for v in args])
        if t.is_array:
            n = len(args)
            out = []
            for k, (base, _) in enumerate(leaves(t.element, e)):
                a = self.fresh("a")
                self.emit(f"{a} = np.empty({n}, {DTYPE[base]})")
                for i, v in enumerate(args):
                    self.emit(f"{a}[{i}] = {v.parts[k]}")
                out.append(Arr(a, 0, n, base))
            return Val(t, out)
        if t.is_struct:
            return Val(t, [p for v in args for p in v.parts])
        comps: list[str] = []
        for v in args:
            comps += [
                self.convert(p, v.t.base if not v.t.is_matrix else "float", t.base or "float")
                for p in v.parts
            ]
        const: list[Any] | None = None
        if all(v.const is not None for v in args):
            const = [c for v in args for c in v.const or ()]  # (none is None)
        if t.is_scalar:
            return Val(t, comps[:1], const[:1] if const else None)
        if t.is_vector:
            if len(comps) == 1:
                c = self.atom(comps[0])
                return Val(t, [c] * t.size, const * t.size if const else None)
            return Val(t, comps[: t.size], const[: t.size] if const else None)
        if t.is_matrix:
            c, r = t.cols, t.rows
            if len(args) == 1 and args[0].t.is_scalar:
                s = self.atom(comps[0])
                zero = self.cf(0.0)
                return Val(t, [s if i == j else zero for i in range(c) for j in range(r)])
            if len(args) == 1 and args[0].t.is_matrix:
                mat = args[0]
                mc, mr = mat.t.cols, mat.t.rows
                one, zero = self.cf(1.0), self.cf(0.0)
                cols: list[Any] = []
                for i in range(c):
                    for j in range(r):
                        if i < mc and j < mr:
                            cols.append(mat.parts[i * mr + j])
                        else:
                            cols.append(one if i == j else zero)
                return Val(t, cols)
            return Val(t, comps[: c * r])
        raise not_yet(f"constructing '{t}'", e)

    def convert(self, p: str, src: str, dst: str) -> str:
        """A scalar converted as runtime.Runtime.to_<dst>: bool to 0/1, float to int through
        cvttps2dq (to_int), float to uint by this CPU's model (driver_profile), the rest by
        their bits or value (numba's casts)."""
        if src == dst:
            return p
        if dst == "bool":
            return f"({p} != 0)"
        if src == "bool":
            one, zero = (
                (self.cf(1.0), self.cf(0.0))
                if dst == "float"
                else (f"{CAST[dst]}(1)", f"{CAST[dst]}(0)")
            )
            return f"({one} if {p} else {zero})"
        if src == "float":
            return f"to_int({p})" if dst == "int" else f"to_uint_{self.float_to_uint}({p})"
        return f"{CAST[dst]}({p})"
