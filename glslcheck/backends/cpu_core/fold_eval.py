"""The terms a call is folded into (cpu_core/call_fold.py): scalar terms, constants folded in
float32, and the evaluator that reads a straight-line callee's statements into one term per
component as NIR sees them after inlining (its rules are listed in call_fold's docstring)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ...semantics.analysis import param_directions
from ...semantics.model import Symbol
from .common import RUNTIME_NAMES
from .host_math import host_sin_cos

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .fold_protocols import FoldEmitter

# built-ins computed component by component (the runtime's function of a scalar array)
_COMPONENTWISE = (
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "exp",
    "exp2",
    "log",
    "log2",
    "sqrt",
    "inversesqrt",
    "abs",
    "sign",
    "floor",
    "ceil",
    "fract",
    "radians",
    "degrees",
)


class Refuse(Exception):
    """The call is not of the shape this module folds."""


class Term:
    """A scalar term: op "k" (a constant: value when known at compile time, else computed by
    args), "x" (a run-time value: code), "*", "+", "/", "neg", "call" (code: the runtime method);
    `comp`: a constant an argument gives (or folded from one), which :meth:`Evaluator.sunk`
    sinks."""

    __slots__ = ("op", "args", "const", "value", "code", "comp")

    def __init__(
        self,
        op: str,
        args: tuple = (),
        const: bool = False,
        value: float | None = None,
        code: str = "",
        comp: bool = False,
    ) -> None:
        self.op, self.args, self.const, self.value, self.code = op, args, const, value, code
        self.comp = comp


def const_term(v: float, comp: bool = False) -> Term:
    return Term("k", const=True, value=float(np.float32(v)), comp=comp)


def fold_tree(op: str, a: float, b: float) -> float:
    with np.errstate(all="ignore"):
        x, y = np.float32(a), np.float32(b)
        return float(x * y if op == "*" else x + y if op == "+" else x / y)


class Evaluator:
    """The scalar evaluation of one call (see the module doc); `merges`: how often a merge rule
    fired."""

    def __init__(self, tr: FoldEmitter, mask: str | None) -> None:
        self.tr, self.mask, self.merges, self.depth, self.factored = tr, mask, 0, 0, 0
        self.slots = 0  # the next free slot of an argument read at run time (_argument_terms)
        # the globals whose values are known where the call starts (:func:`known_globals`), by
        # symbol id, written as the callee writes them; reading any other global refuses
        self.globals: dict[int, list] = {}
        # any other float global is then a value unknown here (UNKNOWN): written, or read into
        # a global's value only (a result or out parameter that reads one refuses: _evaluate)
        self.unknown = False
        self.wrote_global = False  # whether the evaluation assigns a global (`assign`)
        self.holders: list[tuple[int, Any]] = []  # (slot, node) of the values read at run time
        self.opaque = True  # whether a call not followed may be an opaque value (`opaque_call`)
        self.chained: Any = None  # whether a seed chain runs through a function (`opaque_call`)

    # -- scalar rules ----------------------------------------------------------------------
    def neg(self, a: Term) -> Term:
        if a.op == "neg":
            return a.args[0]
        if a.value is not None:
            return const_term(-a.value, a.comp)
        return Term("neg", (a,), const=a.const)

    def mul(self, a: Term, b: Term) -> Term:
        if a.op == "neg" or b.op == "neg":  # (fmul(fneg a, b) -> fneg(fmul(a, b)): the same bits)
            return (
                self.neg(
                    self.mul(a.args[0] if a.op == "neg" else a, b.args[0] if b.op == "neg" else b)
                )
                if (a.op == "neg") != (b.op == "neg")
                else self.mul(a.args[0], b.args[0])
            )
        if a.value is not None and b.value is not None:
            return const_term(fold_tree("*", a.value, b.value), a.comp or b.comp)
        for c, x in ((a, b), (b, a)):
            if c.value is not None and not x.const:
                if c.value == 1.0:
                    return x
                if c.value == -1.0:
                    return self.neg(x)
                if c.value == 0.0:
                    return const_term(0.0)
        for c, x in ((a, b), (b, a)):
            if (
                c.value is not None
                and x.op == "*"
                and x.code == "once"
                and not any(y.const for y in x.args)
            ):
                self.merges += 1  # ~fmul(is_used_once)(fmul(is_used_once)(a, b), #c) -> (a*c) * b
                return self.mul(self.mul(x.args[0], c), x.args[1])
        for c, x in ((a, b), (b, a)):
            if c.const and not x.const and x.op == "*" and (x.args[0].const or x.args[1].const):
                d, y = (x.args[0], x.args[1]) if x.args[0].const else (x.args[1], x.args[0])
                self.merges += 1  # #a * (b * #c) -> (a*c) * b
                return self.mul(self.mul(c, d), y)
        return Term("*", (a, b), const=a.const and b.const)

    def add(self, a: Term, b: Term) -> Term:
        if a.value is not None and b.value is not None:
            return const_term(fold_tree("+", a.value, b.value), a.comp or b.comp)
        for c, x in ((a, b), (b, a)):
            if c.value == 0.0 and not x.const:
                return x
        for c, x in ((a, b), (b, a)):
            if c.const and not x.const and x.op == "+" and (x.args[0].const or x.args[1].const):
                d, y = (x.args[0], x.args[1]) if x.args[0].const else (x.args[1], x.args[0])
                self.merges += 1  # #a + (b + #c) -> (a+c) + b
                return self.add(self.add(c, d), y)
        return Term("+", (a, b), const=a.const and b.const)

    def factored_add(self, a: Term, b: Term) -> Term:
        """``a*b + a*c -> a * (b + c)`` (``('~fadd', ('fmul', a, b), ('fmul', a, c))``), a the same
        value to NIR (its SSA values are shared: :func:`_same`); applied to a dot product's sum,
        where the components of one vector are often the same value: NebulaSmoke's
        ``dot(p3, p3.yzx + 19.19)`` of ``p3 = fract(vec3(p) * K)`` is ``a * (b + (b + b))``
        (measured on llvmpipe; the sum of the three products differs in 6,102 of 14,400 pixels)."""
        if a.op == "*" and b.op == "*" and not a.const and not b.const:
            for i in (0, 1):
                for j in (0, 1):
                    if _same(a.args[i], b.args[j]):
                        self.merges += 1
                        self.factored += 1
                        return self.mul(a.args[i], self.add(a.args[1 - i], b.args[1 - j]))
        return self.add(a, b)

    def pow(self, a: Term, b: Term) -> Term:
        """``pow(#a, #b)`` is folded at compile time by the host's powf (GLSL IR's and NIR's
        constant folding), correctly rounded, not by llvmpipe's exp2(log2) of run time:
        gargantua's ``pcurve(x, 4.0, 0.9)``, ``k = pow(a+b, a+b) / (pow(a,a)*pow(b,b))`` (measured:
        llvmpipe's ``pcurve(0.5, 4.0, 0.9)`` is the float32 of the correctly rounded powers, the
        run-time pow 5 ulps off). Counted as a merge: it changes the written bits."""
        if a.value is not None and b.value is not None:
            self.merges += 1
            with np.errstate(all="ignore"):
                return const_term(
                    float(
                        np.float32(
                            np.float64(np.float32(a.value)) ** np.float64(np.float32(b.value))
                        )
                    )
                )
        if b.value == 4.0:  # (fpow(a, 4.0) -> (a*a)*(a*a), its product used once: `mul`)
            sq = self.mul(a, a)
            return Term("*", (sq, sq), const=a.const, code="once")
        if (
            b.value is not None
        ):  # (Mesa's fpow(a, 2.0) -> a*a, 4.0 -> (a*a)*(a*a): `Runtime.pow_const`)
            return Term("call", (a,), const=a.const, code=f"pow_const({{}}, {b.value!r})")
        return Term("call", (a, b), const=a.const and b.const, code="pow")

    def div(self, a: Term, b: Term) -> Term:
        if a.value is not None and b.value is not None:
            return const_term(fold_tree("/", a.value, b.value), a.comp or b.comp)
        return Term("/", (a, b), const=a.const and b.const)

    def dot(self, u: list[Term], v: list[Term]) -> Term:
        """Runtime.dot: the products summed right to left, each rounded."""
        total = self.mul(u[-1], v[-1])
        for x, y in zip(reversed(u[:-1]), reversed(v[:-1])):
            total = self.factored_add(self.mul(x, y), total)
        return total

    def binary(self, op: str, lt: Any, lv: list[Term], rt: Any, rv: list[Term]) -> list[Term]:
        if op == "*" and lt.is_matrix and (rt.is_vector or rt.is_matrix):
            rows, out = lt.rows, []
            for c in range(rt.cols if rt.is_matrix else 1):
                col = rv[c * lt.cols : (c + 1) * lt.cols]
                for r in range(rows):
                    s = self.mul(lv[r], col[0])
                    for k in range(1, lt.cols):
                        s = self.add(s, self.mul(lv[k * rows + r], col[k]))
                    out.append(s)
            return out
        if op == "*" and lt.is_vector and rt.is_matrix:
            raise Refuse  # (dot products: llvmpipe's order is not copied here)
        n = max(len(lv), len(rv))
        lv, rv = lv * (n // len(lv)), rv * (n // len(rv))
        if op == "+":
            return [self.add(x, y) for x, y in zip(lv, rv)]
        if op == "-":
            return [self.add(x, self.neg(y)) for x, y in zip(lv, rv)]
        if op == "*":
            return [self.mul(x, y) for x, y in zip(lv, rv)]
        if op == "/":
            return [self.div(x, y) for x, y in zip(lv, rv)]
        raise Refuse

    # -- expressions -------------------------------------------------------------------------
    def expr(self, e: Any, env: dict[int, list]) -> list[Term]:
        tr = self.tr
        t = tr.type_of(e)
        if t.is_array or not t.is_struct and t.base not in ("float", "int"):
            raise Refuse  # (effects: an assignment, ++ or a built-in's out argument is refused
            # by its shape below, a user call followed or an opaque value: `call`)
        if t.is_struct:
            size_of(t)  # (float members only, else Refuse)
        else:
            cv = tr.model.const_value(e)
            if cv is not None:
                return [const_term(v) for v in flat_terms(cv)]
            if t.base != "float":
                raise Refuse
        place = self.place(e, env)
        if place is not None:  # (a local or a parameter, a struct's member, a swizzle of one)
            values = self.slot(place[0], env)
            if any(values[i] is None for i in place[1]):
                raise Refuse  # (read before it is written: an out parameter, `S s;`)
            return [values[i] for i in place[1]]
        if isinstance(e, A.Identifier):
            sym = tr.model.symbol_of(e)
            if sym is not None and id(sym) in env:
                if any(x is None for x in env[id(sym)]):
                    raise Refuse  # (an out parameter read before it is written)
                return list(env[id(sym)])
            if sym is None or sym.kind != "uniform":
                raise Refuse
            return [Term("x", code=c) for c in tr.leaves(tr.expr(e, self.mask), t)]
        if isinstance(e, A.Field):
            bt = tr.type_of(e.base)
            base = self.expr(e.base, env)
            if bt.is_struct:
                at, width = _member(bt, e.name)
                return base[at : at + width]
            return [base[i] for i in tr.model.swizzle_indices(e)]
        if isinstance(e, A.Index):
            i = tr.model.const_value(e.index)
            bt = tr.type_of(e.base)
            if not isinstance(i, int) or isinstance(i, bool) or bt.is_array:
                raise Refuse
            base, w = self.expr(e.base, env), (bt.rows if bt.is_matrix else 1)
            return base[i * w : (i + 1) * w]
        if isinstance(e, A.Unary) and e.op in ("-", "+"):
            v = self.expr(e.operand, env)
            return [self.neg(x) for x in v] if e.op == "-" else v
        if isinstance(e, A.Binary):
            return self.binary(
                e.op,
                tr.type_of(e.left),
                self.expr(e.left, env),
                tr.type_of(e.right),
                self.expr(e.right, env),
            )
        if isinstance(e, A.Call):
            return self.call(e, t, env)
        raise Refuse

    def call(self, e: A.Call, t: Any, env: dict[int, list]) -> list[Term]:
        tr = self.tr
        target = tr.model.call_target(e)
        if isinstance(target, Symbol):
            depth, held = self.depth, len(self.holders)
            try:
                return self.user_call(target, e.args, env)
            except Refuse:  # (an opaque call it made inside is not made: it is made whole)
                self.depth, self.holders[held:] = depth, []
                return self.opaque_call(e, t)
        args = [self.expr(a, env) for a in e.args]
        if isinstance(target, B.Overload) and e.callee == "pow" and len(args) == 2:
            return [self.pow(x, y) for x, y in zip(args[0], args[1])]
        if isinstance(target, B.Overload) and e.callee == "dot" and len(args) == 2:
            return [self.dot(args[0], args[1])]
        if isinstance(target, B.Overload) and e.callee == "normalize" and t.is_vector:
            # (Runtime.normalize: x * inversesqrt(dot(x, x)), Mesa's fmul(x, frsq(fdot)))
            rsq = Term("call", (self.dot(args[0], args[0]),), code="inversesqrt")
            return [self.mul(x, rsq) for x in args[0]]
        if isinstance(target, B.Overload) and e.callee == "cross":
            a, b = args  # (Runtime.cross: a.y*b.z - a.z*b.y, ...)
            return [
                self.add(self.mul(a[i], b[j]), self.neg(self.mul(a[j], b[i])))
                for i, j in ((1, 2), (2, 0), (0, 1))
            ]
        if isinstance(target, B.Overload) and e.callee in ("radians", "tan") and len(args) == 1:
            return [self.angle(e.callee, x) for x in args[0]]
        if isinstance(target, B.Overload):
            if e.callee not in _COMPONENTWISE or len(args) != 1:
                raise Refuse
            method = RUNTIME_NAMES.get(e.callee, e.callee)
            return [Term("call", (x,), const=x.const, code=method) for x in args[0]]
        if not e.constructor:
            raise Refuse
        flat = [x for a in args for x in a]
        if t.is_struct:
            if len(flat) != size_of(t):
                raise Refuse
            return flat
        if t.is_vector:
            return flat * t.size if len(flat) == 1 else flat[: t.size]
        if t.is_matrix and len(args) == 1 and len(flat) == 1:
            return [
                flat[0] if c == r else const_term(0.0) for c in range(t.cols) for r in range(t.rows)
            ]
        if t.is_matrix and not any(tr.type_of(a).is_matrix for a in e.args) and len(flat) >= t.size:
            return flat[: t.size]
        if t.is_scalar:
            return flat[:1]
        raise Refuse

    def angle(self, name: str, x: Term) -> Term:
        """``radians`` or ``tan`` of one component, folded at compile time where x is a known
        constant, as NIR folds it after inlining: radians is ``x * (pi/180)`` in float32 (the
        run-time product's bits), tan the host C library's float32 ``sinf(x) / cosf(x)``
        (Mesa's GLSL tan is sin/cos, and fsin, fcos fold with the C library; measured:
        tests/gl/test_llvmpipe_constant_components.py, 95 of 95 constants, gallivm's run-time tan
        75). A folded tan counts as a merge: it may change the written bits."""
        host = host_sin_cos(x.value) if x.value is not None and name == "tan" else None
        if x.value is not None and name == "radians":
            return const_term(fold_tree("*", x.value, np.pi / 180.0), x.comp)
        if host is None:
            return Term("call", (x,), const=x.const, code=RUNTIME_NAMES.get(name, name))
        self.merges += 1
        return const_term(fold_tree("/", *host), x.comp)

    def opaque_call(self, e: A.Call, t: Any) -> list[Term]:
        """A call of a user function without arguments that is not followed (a loop, a global
        written: a random draw advancing a global seed) as a run-time value: the engines make the
        call once, where the folded call's arguments have been read (its slot in `holders`, in
        the order of the callee's statements), and NIR's rules see its result as an unknown
        value, as they see a loop's result after inlining. Not in a struct argument's source
        call (`bound_call`), which is evaluated again at the call that reads it, nor for a
        function a seed chain runs through (`chained`, the engines' nir_fold.repeated_sums
        .chain_params: the caller passes it the chain's base and constants, which the call made
        here would not); none where `chained` is not given (:func:`out_roots`)."""
        target = self.tr.model.call_target(e)
        if (
            not self.opaque
            or self.chained is None
            or e.args
            or t.is_struct
            or t.is_array
            or t.base != "float"
            or not isinstance(target, Symbol)
            or self.chained(target)
        ):
            raise Refuse
        slot = self.slots
        self.slots += 1
        self.holders.append((slot, e))
        # the call may write any global (a seed it advances): none is known after it
        for k, terms in self.globals.items():
            self.globals[k] = [UNKNOWN] * len(terms)
        return leaves_of(f"@{slot}@", t)

    def user_call(self, fn: Symbol, args: list[Any], env: dict[int, list]) -> list[Term]:
        """The callee's result; its out/inout parameters written back into `env`."""
        self.depth += 1
        if self.depth > 16:
            raise Refuse
        params = fn.node.proto.params
        inner: dict[int, list] = {}
        dirs = param_directions(fn)
        for p, a, d in zip(params, args, dirs):
            psym = self.tr.model.symbol_of(p)
            if psym is None:
                raise Refuse
            inner[id(psym)] = (
                self.expr(a, env) if d != "out" else [None] * size_of(self.tr.type_of(a))
            )
        result = self.body(fn, inner)
        for p, a, d in zip(params, args, dirs):
            if d != "in":
                self.assign(a, inner[id(self.tr.model.symbol_of(p))], env)
        self.depth -= 1
        return result

    def bound_call(self, fn: Symbol, values: list[list]) -> list[Term]:
        """The result of `fn` with its (in) parameters bound to the terms `values`."""
        self.depth += 1
        if self.depth > 16:
            raise Refuse
        inner: dict[int, list] = {}
        for p, v in zip(fn.node.proto.params, values):
            psym = self.tr.model.symbol_of(p)
            if psym is None:
                raise Refuse
            inner[id(psym)] = v
        opaque, self.opaque = self.opaque, False
        result = self.body(fn, inner)
        self.opaque = opaque
        self.depth -= 1
        return result

    def sunk(self, outs: list[list]) -> list[list]:
        """`outs` (lists of terms) with an argument's constant sunk down sums as NIR does:
        ``(a + b) + #c -> (a + #c) + b``, each sum used once (its term feeds one term of
        `outs`; a product b kept whole, as is_fmul asks), so that it meets and merges with a
        constant there (``#a + (b + #c) -> (a + c) + b``: a camera's ``ll + s*h + t*v - orig``
        cancels the ``orig.z`` inside ``ll``; nir_fold/sink.py and constant_components.py are
        the rule within one function)."""
        uses: dict[int, int] = {}

        def count(t: Term) -> None:
            uses[id(t)] = uses.get(id(t), 0) + 1
            if uses[id(t)] == 1:
                for a in t.args:
                    count(a)

        for terms in outs:
            for t in terms:
                if t is not None:
                    count(t)
        memo: dict[int, Term] = {}

        def once_sum(t: Term) -> bool:
            return t.op == "+" and uses[id(t)] == 1 and not any(a.const for a in t.args)

        def push(a: Term, c: Term) -> Term:
            if once_sum(a):
                p, q = a.args
                if q.op != "*" and p.op == "*":
                    p, q = q, p
                self.merges += 1
                return self.add(push(p, c), walk(q))
            return self.add(walk(a), c)

        def walk(t: Term) -> Term:
            if id(t) not in memo:
                x = t
                if t.op == "+" and uses[id(t)] == 1:
                    for c, a in (t.args, t.args[::-1]):
                        if c.value is not None and c.comp and once_sum(a):
                            x = push(a, c)
                            break
                if x is t and t.args:
                    args = tuple(walk(a) for a in t.args)
                    if any(a is not b for a, b in zip(args, t.args)):
                        x = Term(t.op, args, t.const, t.value, t.code, t.comp)
                memo[id(t)] = x
            return memo[id(t)]

        return [[None if t is None else walk(t) for t in terms] for terms in outs]

    def body(self, fn: Symbol, env: dict[int, list]) -> list[Term]:
        stmts = fn.node.body.stmts
        for i, st in enumerate(stmts):
            if isinstance(st, A.Return) and i == len(stmts) - 1:
                return self.expr(st.value, env) if st.value is not None else []
            if isinstance(st, A.DeclarationStatement) and isinstance(
                st.decl, A.VariableDeclaration
            ):
                for d in st.decl.declarators:
                    sym = self.tr.model.symbol_of(d)
                    if sym is None or d.array is not None:
                        raise Refuse
                    env[id(sym)] = (
                        self.expr(d.init, env) if d.init is not None else [None] * size_of(sym.type)
                    )
            elif isinstance(st, A.ExpressionStatement) and isinstance(st.expr, A.Assignment):
                a = st.expr
                value = self.expr(a.value, env)
                if a.op != "=":
                    value = self.binary(
                        a.op[:-1],
                        self.tr.type_of(a.target),
                        self.expr(a.target, env),
                        self.tr.type_of(a.value),
                        value,
                    )
                self.assign(a.target, value, env)
            elif (
                isinstance(st, A.ExpressionStatement)
                and isinstance(st.expr, (A.Unary, A.Postfix))
                and st.expr.op in ("++", "--")
            ):  # (a float ++ or --: x += 1.0, x -= 1.0; expr refuses any other type)
                x = st.expr.operand
                value = [
                    self.add(v, const_term(1.0 if st.expr.op == "++" else -1.0))
                    for v in self.expr(x, env)
                ]
                self.assign(x, value, env)
            elif (
                isinstance(st, A.ExpressionStatement)
                and isinstance(st.expr, A.Call)
                and isinstance(target := self.tr.model.call_target(st.expr), Symbol)
            ):
                self.user_call(target, st.expr.args, env)
            else:
                raise Refuse
        return []  # (a function that returns a value ends with a return: checked by the checker)

    def assign(self, target: Any, value: list[Term], env: dict[int, list]) -> None:
        place = self.place(target, env)
        if place is None:
            raise Refuse
        key, idx = place
        store = env if key in env else self.globals
        self.wrote_global = self.wrote_global or store is self.globals
        new = list(store[key])
        for i, v in zip(idx, value * len(idx) if len(value) == 1 else value):
            new[i] = v
        store[key] = new

    def slot(self, key: int, env: dict[int, list]) -> list:
        """The terms of the variable `key` of :meth:`place`: a local or parameter of `env`, else a
        known global."""
        return env[key] if key in env else self.globals[key]

    def place(self, e: Any, env: dict[int, list]) -> tuple[int, list[int]] | None:
        """(the key in `env`, the indexes of the components) of a local or parameter of the
        evaluation, a member of such a struct or a swizzle of such a vector; else None."""
        tr = self.tr
        if isinstance(e, A.Identifier):
            sym = tr.model.symbol_of(e)
            if sym is None or id(sym) not in env and id(sym) not in self.globals:
                if not (self.unknown and float_global(sym)):
                    return None
                self.globals[id(sym)] = [UNKNOWN] * size_of(sym.type)
            return id(sym), list(range(len(self.slot(id(sym), env))))
        if isinstance(e, A.Field):
            base = self.place(e.base, env)
            if base is None:
                return None
            bt = tr.type_of(e.base)
            if bt.is_struct:
                at, width = _member(bt, e.name)
                return base[0], base[1][at : at + width]
            if not tr.model.is_swizzle(e):
                raise Refuse
            return base[0], [base[1][i] for i in tr.model.swizzle_indices(e)]
        return None


def _same(a: Term, b: Term) -> bool:
    """The two terms are one value to NIR (the same operation of the same operands: its CSE)."""
    if a is b:
        return True
    if a.op != b.op or a.code != b.code or len(a.args) != len(b.args):
        return False
    if a.op == "k":
        return a.value is not None and a.value == b.value and not a.args
    return all(_same(x, y) for x, y in zip(a.args, b.args))


def flat_terms(v: Any) -> list[float]:
    if isinstance(v, (tuple, list)):
        return [x for item in v for x in flat_terms(item)]
    if isinstance(v, bool):
        raise Refuse
    return [float(v)]


def holder_leaf(code: str) -> tuple[int, tuple[int, ...]] | None:
    """(argument i, the indexes after it) of a term's code ``@i@[c][r]`` (:func:`leaves_of`), or
    None for the code of a value the engine computed (a uniform the callee reads)."""
    if not code.startswith("@"):
        return None
    i, _, rest = code[1:].partition("@")
    return int(i), tuple(int(x) for x in rest.replace("]", "").split("[")[1:])


def term_fields(t: Any) -> tuple[str, tuple, float | None, str]:
    """(op, args, value, code) of a term of :func:`fold_plan` (module doc: "k" a constant, "x" a
    run-time value, "*", "+", "/", "neg", "call" of the Runtime's method `code`)."""
    return t.op, t.args, t.value, t.code


def width_of(t: Any) -> int:
    return t.size if t.is_matrix or t.is_vector else 1


def size_of(t: Any) -> int:
    """The float components of a value of type t, a struct's members one after the other;
    raises Refuse for a struct with a member that is not a float scalar, vector or matrix."""
    if t.is_struct:
        return sum(size_of(ft) for _, ft in t.fields)
    if t.is_array or t.base != "float":
        raise Refuse
    return width_of(t)


def member_size(t: Any) -> int:
    """The number of terms a value of type t (a member of a folded call's struct result, all
    of whose members are float: :func:`fold_plan` checked) takes."""
    return size_of(t)


def _member(t: Any, name: str) -> tuple[int, int]:
    """(offset, width) of the member `name` among the components of the struct type t."""
    at = 0
    for fname, ft in t.fields:
        if fname == name:
            return at, size_of(ft)
        at += size_of(ft)
    raise Refuse


def leaves_of(code: str, t: Any) -> list[Term]:
    """The run-time components of the argument whose placeholder is `code` (``@i@``: argument
    i, replaced by its value's code when emitted; :func:`holder_leaf` reads it back)."""
    if t.is_scalar:
        return [Term("x", code=code)]
    if t.is_vector:
        return [Term("x", code=f"{code}[{i}]") for i in range(t.size)]
    return [Term("x", code=f"{code}[{c}][{r}]") for c in range(t.cols) for r in range(t.rows)]


UNKNOWN = Term("x", code="@global@")  # a global's value where it is not known (Evaluator.unknown)


def float_global(sym: Symbol) -> bool:
    """A global variable (no `const`, no uniform) of float, vecN or matN."""
    t = sym.type
    return (
        sym.kind == "global"
        and sym.qualifier is None
        and sym.const_value is None
        and not t.is_array
        and not t.is_struct
        and t.base == "float"
    )
