"""Constants propagated into a call, per call site and per component, as NIR does after inlining.

Mesa inlines every function before its optimisations run (nir_inline_functions), scalarises
vectors and matrices (nir_lower_alu_to_scalar), then nir_opt_constant_folding and
nir_opt_algebraic work on each component's SSA value. So a vector argument whose components
are partly compile-time constants at one call site carries those constants into the callee's
arithmetic, and Mesa's constant-merging rules then reach across the call. The real shader
that shows it (gargantua, lstSRS, Buffer A):

    vec3 rotate(vec3 p, float x, float y, float z) { mat3 matx = mat3(1.0, 0.0, 0.0, 0.0,
        cos(x), sin(x), 0.0, -sin(x), cos(x)); ...  p = matx * p; p = matz * p; p = maty * p; }
    void RotateCamera(inout vec3 eyevec, inout vec3 eyepos) { ... vec3 angle = vec3(..., -0.45);
        eyepos = rotate(eyepos, angle.x, angle.y, angle.z); }
    ... vec3 eyepos = vec3(0.0, -0.0, -10.0); eyepos.x += ...; RotateCamera(eyevec, eyepos);

eyepos's y and z are -0.0 and -10.0 at the call, so the products by matx's zeros fold away
and ``matz * p`` multiplies the constant ``cos(-0.45)`` by ``-sin(ax) * -10.0``: NIR's
``#a * (b * #c) -> (a*c) * b`` gives ``(cos(-0.45) * 10) * sin(ax)`` (measured: llvmpipe's
eyepos.y is ``sin(-0.45)*x + (cos(-0.45)*10)*sin(ax)`` bit for bit). The NumPy backend writes a
function once for every call, so its code cannot see the constants of one call site.

Here a call of a straight-line function (declarations, assignments and a final return; nested
calls of such functions) is evaluated at the call site as NIR sees it: one scalar term per
component, the arguments' compile-time constant components (literals, a vector constructor's
constant arguments, and a local's components that are constant where the call reads them:
`_constant_components`) as constants, an argument
``y * #c`` as that product in each component (`_scaled_argument`), then

- constants folded in float32 (``+ - * /``, negation; a built-in of constants is a constant
  computed by the runtime's own function, as the written code computes it, but ``radians``
  and ``tan``, folded at compile time as Mesa does: :meth:`_Eval.angle`);
- ``a * 1.0 -> a``, ``a * -1.0 -> -a``, ``a * 0.0 -> 0.0`` (inexact, a not constant),
  ``a + 0.0 -> a``;
- constants merged: ``#a * (b * #c) -> (a*c) * b`` and ``#a + (b + #c) -> (a+c) + b``;
- matrix products in GLSL IR's order (``m * v`` is ``(m[0]*v.x + m[1]*v.y) + m[2]*v.z`` per
  row), component-wise built-ins (sin, cos, ...) per component;
- ``dot`` summed right to left as Runtime.dot, two products that share a value factored,
  ``a*b + a*c -> a * (b + c)`` (`_Eval.factored_add`: a hash's ``vec3(p)`` has three equal
  components).

Only where a merge happens (the other folds give the written bits, up to a -0.0, a NaN or an
infinity times a constant zero, which `Runtime.fmul`/`fadd` already fold at run time) is the
call replaced, in llvmpipe mode only: ``if rt.lp:`` the folded components, ``else:`` the call
as written, so the float64 reference and float16 keep the written order.

Structs of float members are values of their members' components one after the other (a
member read or written is a slice; ``S r;`` declares it unknown until written), ``normalize``
is ``x * inversesqrt(dot(x, x))`` and ``cross`` is Runtime.cross, per component. A struct
argument is followed where it is a local initialised by a call of such a function
(``cam k = make(vec3(off, -6.0), 7.0); ... ray(k, s, t)``): that call is evaluated again at
the call, its arguments read there (:func:`.call_sites.struct_source` checks that nothing
they read is written in between), so the constant -6.0 reaches ``ray``'s arithmetic as it
does after NIR inlines both. An argument's constant is also sunk down sums each used once,
``(a + b) + #c -> (a + #c) + b`` (:meth:`_Eval.sunk`), where it cancels a constant of the same
component (the camera ray's ``ll + s*h + t*v - orig``, measured:
tests/gl/test_llvmpipe_constant_components.py). A call returning a struct of float members
is folded where an argument carries a constant (``ray get_ray(camera k, float s, float t)``:
the engines build the struct from its members' terms); a call writing a struct through an
out argument is left as written.

A call without arguments inside the callee that is not followed (a loop, a global written:
p05-3lccz8's ``cam.lens_radius * random_in_unit_disk()``, whose loop advances the global seed)
is an unknown value to NIR's rules after inlining, as a loop's result is: it is a run-time
value of the terms, the call made once by the engines among the values read at run time
(after the folded call's arguments, in the order of the callee's statements:
:meth:`_Eval.opaque_call`).

Not copied: calls under a loop or a branch of the caller whose constants come from there (a
local counts as constant only where its writes are top-level statements before the call),
callees with branches, loops, arrays or non-float arithmetic, ``vec * mat``, and the other
rewrites that need "used once" (nir_fold's sink and sunk_return stay the rules within a
function).

What it tells nir_fold about a folded call's results: :func:`out_roots` (the operation at the
root of each component, so ``(eyevec * dither) * far`` may move its constant: eyevec is a
sum to NIR) and :func:`product_sums` (the two products of a component ``p1 + p2``, for
``(p1 + e) + p2``).

It does not replace the two older rules that reach across a call. inline.py's inlining for
``merged_dot`` needs the caller's never-written local seen through (``uv = q * 1.2`` passed as
``uv * 0.2``) and a ``dot`` with a constant merged, neither evaluated here (an argument that
is not a constant component is a run-time value); nir_fold.sunk_return sinks a constant into
a ``+=`` chain, a rewrite that needs "used once", not copied here. Both stay as they are, and
their generated code is unchanged.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ...semantics.analysis import param_directions
from ...semantics.model import Symbol
from .call_sites import struct_source, unchanged_init, written_components
from .common import RUNTIME_NAMES
from .host_math import host_sin_cos

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .fold_protocols import FoldEmitter, FoldEngine

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


class _Refuse(Exception):
    """The call is not of the shape this module folds."""


class _T:
    """A scalar term: op "k" (a constant: value when known at compile time, else computed by
    args), "x" (a run-time value: code), "*", "+", "/", "neg", "call" (code: the runtime method);
    `comp`: a constant an argument gives (or folded from one), which :meth:`_Eval.sunk` sinks."""

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


def _k(v: float, comp: bool = False) -> _T:
    return _T("k", const=True, value=float(np.float32(v)), comp=comp)


def fold_tree(op: str, a: float, b: float) -> float:
    with np.errstate(all="ignore"):
        x, y = np.float32(a), np.float32(b)
        return float(x * y if op == "*" else x + y if op == "+" else x / y)


class _Eval:
    """The scalar evaluation of one call (see the module doc); `merges`: how often a merge rule
    fired."""

    def __init__(self, tr: FoldEmitter, mask: str | None) -> None:
        self.tr, self.mask, self.merges, self.depth, self.factored = tr, mask, 0, 0, 0
        self.slots = 0  # the next free slot of an argument read at run time (_argument_terms)
        # the globals whose values are known where the call starts (:func:`known_globals`), by
        # symbol id, written as the callee writes them; reading any other global refuses
        self.globals: dict[int, list] = {}
        # any other float global is then a value unknown here (_UNKNOWN): written, or read into
        # a global's value only (a result or out parameter that reads one refuses: _evaluate)
        self.unknown = False
        self.holders: list[tuple[int, Any]] = []  # (slot, node) of the values read at run time
        self.opaque = True  # whether a call not followed may be an opaque value (`opaque_call`)
        self.chained: Any = None  # whether a seed chain runs through a function (`opaque_call`)

    # -- scalar rules ----------------------------------------------------------------------
    def neg(self, a: _T) -> _T:
        if a.op == "neg":
            return a.args[0]
        if a.value is not None:
            return _k(-a.value, a.comp)
        return _T("neg", (a,), const=a.const)

    def mul(self, a: _T, b: _T) -> _T:
        if a.op == "neg" or b.op == "neg":  # (fmul(fneg a, b) -> fneg(fmul(a, b)): the same bits)
            return (
                self.neg(
                    self.mul(a.args[0] if a.op == "neg" else a, b.args[0] if b.op == "neg" else b)
                )
                if (a.op == "neg") != (b.op == "neg")
                else self.mul(a.args[0], b.args[0])
            )
        if a.value is not None and b.value is not None:
            return _k(fold_tree("*", a.value, b.value), a.comp or b.comp)
        for c, x in ((a, b), (b, a)):
            if c.value is not None and not x.const:
                if c.value == 1.0:
                    return x
                if c.value == -1.0:
                    return self.neg(x)
                if c.value == 0.0:
                    return _k(0.0)
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
        return _T("*", (a, b), const=a.const and b.const)

    def add(self, a: _T, b: _T) -> _T:
        if a.value is not None and b.value is not None:
            return _k(fold_tree("+", a.value, b.value), a.comp or b.comp)
        for c, x in ((a, b), (b, a)):
            if c.value == 0.0 and not x.const:
                return x
        for c, x in ((a, b), (b, a)):
            if c.const and not x.const and x.op == "+" and (x.args[0].const or x.args[1].const):
                d, y = (x.args[0], x.args[1]) if x.args[0].const else (x.args[1], x.args[0])
                self.merges += 1  # #a + (b + #c) -> (a+c) + b
                return self.add(self.add(c, d), y)
        return _T("+", (a, b), const=a.const and b.const)

    def factored_add(self, a: _T, b: _T) -> _T:
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

    def pow(self, a: _T, b: _T) -> _T:
        """``pow(#a, #b)`` is folded at compile time by the host's powf (GLSL IR's and NIR's
        constant folding), correctly rounded, not by llvmpipe's exp2(log2) of run time:
        gargantua's ``pcurve(x, 4.0, 0.9)``, ``k = pow(a+b, a+b) / (pow(a,a)*pow(b,b))`` (measured:
        llvmpipe's ``pcurve(0.5, 4.0, 0.9)`` is the float32 of the correctly rounded powers, the
        run-time pow 5 ulps off). Counted as a merge: it changes the written bits."""
        if a.value is not None and b.value is not None:
            self.merges += 1
            with np.errstate(all="ignore"):
                return _k(
                    float(
                        np.float32(
                            np.float64(np.float32(a.value)) ** np.float64(np.float32(b.value))
                        )
                    )
                )
        if b.value == 4.0:  # (fpow(a, 4.0) -> (a*a)*(a*a), its product used once: `mul`)
            sq = self.mul(a, a)
            return _T("*", (sq, sq), const=a.const, code="once")
        if (
            b.value is not None
        ):  # (Mesa's fpow(a, 2.0) -> a*a, 4.0 -> (a*a)*(a*a): `Runtime.pow_const`)
            return _T("call", (a,), const=a.const, code=f"pow_const({{}}, {b.value!r})")
        return _T("call", (a, b), const=a.const and b.const, code="pow")

    def div(self, a: _T, b: _T) -> _T:
        if a.value is not None and b.value is not None:
            return _k(fold_tree("/", a.value, b.value), a.comp or b.comp)
        return _T("/", (a, b), const=a.const and b.const)

    def dot(self, u: list[_T], v: list[_T]) -> _T:
        """Runtime.dot: the products summed right to left, each rounded."""
        total = self.mul(u[-1], v[-1])
        for x, y in zip(reversed(u[:-1]), reversed(v[:-1])):
            total = self.factored_add(self.mul(x, y), total)
        return total

    def binary(self, op: str, lt: Any, lv: list[_T], rt: Any, rv: list[_T]) -> list[_T]:
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
            raise _Refuse  # (dot products: llvmpipe's order is not copied here)
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
        raise _Refuse

    # -- expressions -------------------------------------------------------------------------
    def expr(self, e: Any, env: dict[int, list]) -> list[_T]:
        tr = self.tr
        t = tr.type_of(e)
        if t.is_array or not t.is_struct and t.base not in ("float", "int"):
            raise _Refuse  # (effects: an assignment, ++ or a built-in's out argument is refused
            # by its shape below, a user call followed or an opaque value: `call`)
        if t.is_struct:
            _size(t)  # (float members only, else _Refuse)
        else:
            cv = tr.model.const_value(e)
            if cv is not None:
                return [_k(v) for v in _flat(cv)]
            if t.base != "float":
                raise _Refuse
        place = self.place(e, env)
        if place is not None:  # (a local or a parameter, a struct's member, a swizzle of one)
            values = self.slot(place[0], env)
            if any(values[i] is None for i in place[1]):
                raise _Refuse  # (read before it is written: an out parameter, `S s;`)
            return [values[i] for i in place[1]]
        if isinstance(e, A.Identifier):
            sym = tr.model.symbol_of(e)
            if sym is not None and id(sym) in env:
                if any(x is None for x in env[id(sym)]):
                    raise _Refuse  # (an out parameter read before it is written)
                return list(env[id(sym)])
            if sym is None or sym.kind != "uniform":
                raise _Refuse
            return [_T("x", code=c) for c in tr.leaves(tr.expr(e, self.mask), t)]
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
                raise _Refuse
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
        raise _Refuse

    def call(self, e: A.Call, t: Any, env: dict[int, list]) -> list[_T]:
        tr = self.tr
        target = tr.model.call_target(e)
        if isinstance(target, Symbol):
            depth, held = self.depth, len(self.holders)
            try:
                return self.user_call(target, e.args, env)
            except _Refuse:  # (an opaque call it made inside is not made: it is made whole)
                self.depth, self.holders[held:] = depth, []
                return self.opaque_call(e, t)
        args = [self.expr(a, env) for a in e.args]
        if isinstance(target, B.Overload) and e.callee == "pow" and len(args) == 2:
            return [self.pow(x, y) for x, y in zip(args[0], args[1])]
        if isinstance(target, B.Overload) and e.callee == "dot" and len(args) == 2:
            return [self.dot(args[0], args[1])]
        if isinstance(target, B.Overload) and e.callee == "normalize" and t.is_vector:
            # (Runtime.normalize: x * inversesqrt(dot(x, x)), Mesa's fmul(x, frsq(fdot)))
            rsq = _T("call", (self.dot(args[0], args[0]),), code="inversesqrt")
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
                raise _Refuse
            method = RUNTIME_NAMES.get(e.callee, e.callee)
            return [_T("call", (x,), const=x.const, code=method) for x in args[0]]
        if not e.constructor:
            raise _Refuse
        flat = [x for a in args for x in a]
        if t.is_struct:
            if len(flat) != _size(t):
                raise _Refuse
            return flat
        if t.is_vector:
            return flat * t.size if len(flat) == 1 else flat[: t.size]
        if t.is_matrix and len(args) == 1 and len(flat) == 1:
            return [flat[0] if c == r else _k(0.0) for c in range(t.cols) for r in range(t.rows)]
        if t.is_matrix and not any(tr.type_of(a).is_matrix for a in e.args) and len(flat) >= t.size:
            return flat[: t.size]
        if t.is_scalar:
            return flat[:1]
        raise _Refuse

    def angle(self, name: str, x: _T) -> _T:
        """``radians`` or ``tan`` of one component, folded at compile time where x is a known
        constant, as NIR folds it after inlining: radians is ``x * (pi/180)`` in float32 (the
        run-time product's bits), tan the host C library's float32 ``sinf(x) / cosf(x)``
        (Mesa's GLSL tan is sin/cos, and fsin, fcos fold with the C library; measured:
        tests/gl/test_llvmpipe_constant_components.py, 95 of 95 constants, gallivm's run-time tan
        75). A folded tan counts as a merge: it may change the written bits."""
        host = host_sin_cos(x.value) if x.value is not None and name == "tan" else None
        if x.value is not None and name == "radians":
            return _k(fold_tree("*", x.value, np.pi / 180.0), x.comp)
        if host is None:
            return _T("call", (x,), const=x.const, code=RUNTIME_NAMES.get(name, name))
        self.merges += 1
        return _k(fold_tree("/", *host), x.comp)

    def opaque_call(self, e: A.Call, t: Any) -> list[_T]:
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
            raise _Refuse
        slot = self.slots
        self.slots += 1
        self.holders.append((slot, e))
        return _leaves(f"@{slot}@", t)

    def user_call(self, fn: Symbol, args: list[Any], env: dict[int, list]) -> list[_T]:
        """The callee's result; its out/inout parameters written back into `env`."""
        self.depth += 1
        if self.depth > 16:
            raise _Refuse
        params = fn.node.proto.params
        inner: dict[int, list] = {}
        dirs = param_directions(fn)
        for p, a, d in zip(params, args, dirs):
            psym = self.tr.model.symbol_of(p)
            if psym is None:
                raise _Refuse
            inner[id(psym)] = (
                self.expr(a, env) if d != "out" else [None] * _size(self.tr.type_of(a))
            )
        result = self.body(fn, inner)
        for p, a, d in zip(params, args, dirs):
            if d != "in":
                self.assign(a, inner[id(self.tr.model.symbol_of(p))], env)
        self.depth -= 1
        return result

    def bound_call(self, fn: Symbol, values: list[list]) -> list[_T]:
        """The result of `fn` with its (in) parameters bound to the terms `values`."""
        self.depth += 1
        if self.depth > 16:
            raise _Refuse
        inner: dict[int, list] = {}
        for p, v in zip(fn.node.proto.params, values):
            psym = self.tr.model.symbol_of(p)
            if psym is None:
                raise _Refuse
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

        def count(t: _T) -> None:
            uses[id(t)] = uses.get(id(t), 0) + 1
            if uses[id(t)] == 1:
                for a in t.args:
                    count(a)

        for terms in outs:
            for t in terms:
                if t is not None:
                    count(t)
        memo: dict[int, _T] = {}

        def once_sum(t: _T) -> bool:
            return t.op == "+" and uses[id(t)] == 1 and not any(a.const for a in t.args)

        def push(a: _T, c: _T) -> _T:
            if once_sum(a):
                p, q = a.args
                if q.op != "*" and p.op == "*":
                    p, q = q, p
                self.merges += 1
                return self.add(push(p, c), walk(q))
            return self.add(walk(a), c)

        def walk(t: _T) -> _T:
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
                        x = _T(t.op, args, t.const, t.value, t.code, t.comp)
                memo[id(t)] = x
            return memo[id(t)]

        return [[None if t is None else walk(t) for t in terms] for terms in outs]

    def body(self, fn: Symbol, env: dict[int, list]) -> list[_T]:
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
                        raise _Refuse
                    env[id(sym)] = (
                        self.expr(d.init, env) if d.init is not None else [None] * _size(sym.type)
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
                    self.add(v, _k(1.0 if st.expr.op == "++" else -1.0)) for v in self.expr(x, env)
                ]
                self.assign(x, value, env)
            elif (
                isinstance(st, A.ExpressionStatement)
                and isinstance(st.expr, A.Call)
                and isinstance(target := self.tr.model.call_target(st.expr), Symbol)
            ):
                self.user_call(target, st.expr.args, env)
            else:
                raise _Refuse
        return []  # (a function that returns a value ends with a return: checked by the checker)

    def assign(self, target: Any, value: list[_T], env: dict[int, list]) -> None:
        place = self.place(target, env)
        if place is None:
            raise _Refuse
        key, idx = place
        store = env if key in env else self.globals
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
                if not (self.unknown and _float_global(sym)):
                    return None
                self.globals[id(sym)] = [_UNKNOWN] * _size(sym.type)
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
                raise _Refuse
            return base[0], [base[1][i] for i in tr.model.swizzle_indices(e)]
        return None


def _same(a: _T, b: _T) -> bool:
    """The two terms are one value to NIR (the same operation of the same operands: its CSE)."""
    if a is b:
        return True
    if a.op != b.op or a.code != b.code or len(a.args) != len(b.args):
        return False
    if a.op == "k":
        return a.value is not None and a.value == b.value and not a.args
    return all(_same(x, y) for x, y in zip(a.args, b.args))


def _flat(v: Any) -> list[float]:
    if isinstance(v, (tuple, list)):
        return [x for item in v for x in _flat(item)]
    if isinstance(v, bool):
        raise _Refuse
    return [float(v)]


def holder_leaf(code: str) -> tuple[int, tuple[int, ...]] | None:
    """(argument i, the indexes after it) of a term's code ``@i@[c][r]`` (:func:`_leaves`), or
    None for the code of a value the engine computed (a uniform the callee reads)."""
    if not code.startswith("@"):
        return None
    i, _, rest = code[1:].partition("@")
    return int(i), tuple(int(x) for x in rest.replace("]", "").split("[")[1:])


def term_fields(t: Any) -> tuple[str, tuple, float | None, str]:
    """(op, args, value, code) of a term of :func:`fold_plan` (module doc: "k" a constant, "x" a
    run-time value, "*", "+", "/", "neg", "call" of the Runtime's method `code`)."""
    return t.op, t.args, t.value, t.code


def _width(t: Any) -> int:
    return t.size if t.is_matrix or t.is_vector else 1


def _size(t: Any) -> int:
    """The float components of a value of type t, a struct's members one after the other;
    raises _Refuse for a struct with a member that is not a float scalar, vector or matrix."""
    if t.is_struct:
        return sum(_size(ft) for _, ft in t.fields)
    if t.is_array or t.base != "float":
        raise _Refuse
    return _width(t)


def member_size(t: Any) -> int:
    """The number of terms a value of type t (a member of a folded call's struct result, all
    of whose members are float: :func:`fold_plan` checked) takes."""
    return _size(t)


def _member(t: Any, name: str) -> tuple[int, int]:
    """(offset, width) of the member `name` among the components of the struct type t."""
    at = 0
    for fname, ft in t.fields:
        if fname == name:
            return at, _size(ft)
        at += _size(ft)
    raise _Refuse


def _leaves(code: str, t: Any) -> list[_T]:
    """The run-time components of the argument whose placeholder is `code` (``@i@``: argument
    i, replaced by its value's code when emitted; :func:`holder_leaf` reads it back)."""
    if t.is_scalar:
        return [_T("x", code=code)]
    if t.is_vector:
        return [_T("x", code=f"{code}[{i}]") for i in range(t.size)]
    return [_T("x", code=f"{code}[{c}][{r}]") for c in range(t.cols) for r in range(t.rows)]


def _constant_components(tr: FoldEmitter, arg: Any, call: A.Call) -> list[_T | None] | None:
    """Per component of an argument `arg` of `call`, a vector constructor or a local: a
    constant term where its value is a compile-time constant there, else None; None when `arg`
    is neither. A constructor's constant arguments are its constant components
    (``f(vec2(x, 1.5))``: NIR's inlined ``p.y`` is 1.5). A local's are known only for a local
    declared, then written, by top-level statements of the current function before the one
    that holds `call` (writes of single components keep the others)."""
    if isinstance(arg, A.Call):
        t = tr.type_of(arg)
        if not (arg.constructor and t.is_vector and t.base == "float" and len(arg.args) > 1):
            return None
        return _constructed_components(tr, arg, t)
    sym = tr.model.symbol_of(arg) if isinstance(arg, A.Identifier) else None
    if (
        sym is None
        or sym.kind != "local"
        or not isinstance(sym.node, A.Declarator)
        or sym.node.init is None
    ):
        return None
    assert tr.fn is not None  # folding a call inside a function
    stmts = tr.fn.sym.node.body.stmts
    decl = next((i for i, st in enumerate(stmts) if any(n is sym.node for n in st.walk())), None)
    at = next((i for i, st in enumerate(stmts) if any(n is call for n in st.walk())), None)
    if decl is None or at is None or not isinstance(stmts[decl], A.DeclarationStatement):
        return None
    init, t = sym.node.init, tr.type_of(arg)
    if t.is_array or t.is_struct or t.base != "float":
        return None
    cv = tr.model.const_value(init)
    if cv is not None:
        comps: list[_T | None] = [_k(v, True) for v in _flat(cv)]
    elif isinstance(init, A.Call) and init.constructor and t.is_vector and len(init.args) > 1:
        comps = _constructed_components(tr, init, t)
    else:
        return None
    for st in stmts[decl + 1 : at + 1]:
        for n in st.walk():
            hit = written_components(tr, n, sym, call)
            if hit == "all":
                comps = [None] * len(comps)
            elif hit:
                for i in hit:
                    comps[i] = None
    return comps


def _constructed_components(tr: FoldEmitter, ctor: A.Call, t: Any) -> list[_T | None]:
    """Per component of the vector constructor `ctor` (of type `t`): its constant term, or None
    where an argument is not a compile-time constant."""
    comps: list[_T | None] = []
    for a in ctor.args:
        v = tr.model.const_value(a)
        comps += (
            [_k(x, True) for x in _flat(v)] if v is not None else [None] * _width(tr.type_of(a))
        )
    return comps[: t.size]


def fold_plan(
    tr: FoldEmitter, call: A.Call, fn: Symbol, mask: str | None, chained: Any = None
) -> tuple | None:
    """(the parameters' final terms by symbol id, the parameter symbols, the result's terms,
    the arguments read at run time as (index, node)) of the call `call` of user function `fn`
    evaluated with constants propagated as NIR does (module doc: each engine emits the terms);
    None where this call is left as written (the common case): no argument has a constant
    component, or the constants merge no more than they do with every argument a run-time value
    (merges inside the callee alone are nir_fold's, in the function's own code), and no dot
    product of the callee factors (``vec3(p.xyx)`` of Dave Hoskins' hash12: two products share
    p.x). `chained(fn)`: whether a seed chain runs through user function fn (the engines
    pass nir_fold.repeated_sums.chain_params, which imports this module: _Eval.opaque_call)."""
    if (
        tr.fn is None
        or tr.fold_state.call_fold_off
        or tr.fold_state.inline_frames
        or any(tr.has_effects(a) for a in call.args)
        or any(d != "in" and tr.type_of(a).is_struct for a, (_, _, d) in zip(call.args, fn.params))
    ):
        return None
    try:
        constant = _has_constant_argument(tr, call, fn)
        if not constant and (tr.type_of(call).is_struct or not _calls_dot(tr, fn)):
            return None  # (a struct result: only where an argument carries a constant)
        ev, env, params, result, holders = _evaluate(tr, call, fn, mask, True, chained)
        if (
            ev.factored == 0
        ):  # (a factored dot product is folded here only: Runtime.dot keeps the products)
            if not constant or ev.merges == 0:
                return None
            if _evaluate(tr, call, fn, mask, False, chained)[0].merges >= ev.merges:
                return None
    except _Refuse:
        return None
    return env, params, result, holders


def _calls_dot(tr: FoldEngine, fn: Symbol) -> bool:
    """`fn`'s body calls the built-in dot (where :meth:`_Eval.factored_add` may apply)."""
    memo = tr.fold_state.call_fold_dots
    if id(fn) not in memo:
        memo[id(fn)] = any(
            isinstance(n, A.Call)
            and n.callee == "dot"
            and isinstance(tr.model.call_target(n), B.Overload)
            for n in fn.node.body.walk()
        )
    return memo[id(fn)]


def _has_constant_argument(tr: FoldEmitter, call: A.Call, fn: Symbol) -> bool:
    for a, (_, _, dr) in zip(call.args, fn.params):
        if dr == "in" and tr.type_of(a).is_struct:
            source = struct_source(tr, a, call)
            inner = tr.model.call_target(source) if source is not None else None
            if (
                source is not None
                and isinstance(inner, Symbol)
                and _has_constant_argument(tr, source, inner)
            ):
                return True
        elif dr != "out" and (
            tr.model.const_value(a) is not None
            or _scaled_argument(tr, a, call) is not None
            or any(k is not None for k in _constant_components(tr, a, call) or ())
        ):
            return True
    return False


def _scaled_argument(tr: FoldEmitter, a: Any, call: A.Call) -> tuple[Any, Any] | None:
    """(y, #c) for an argument written ``y * #c`` or ``#c * y`` (c a compile-time constant of
    y's type or a scalar, y not constant, no matrix): after inlining each component of the
    parameter is that product, into which NIR merges the callee's constants (NebulaSmoke's
    ``hash11(fi * 0.017)`` with ``fract(vec3(p) * 443.8975)``: ``fi * (0.017*443.8975)``), also
    through a local so initialised that nothing writes before `call` (NIR's SSA value)."""
    if isinstance(a, A.Identifier):
        a = unchanged_init(tr, a, call)
    if not (isinstance(a, A.Binary) and a.op == "*") or tr.has_effects(a):
        return None
    for y, c in ((a.left, a.right), (a.right, a.left)):
        ty, tc = tr.type_of(y), tr.type_of(c)
        if (
            tr.model.const_value(c) is not None
            and tr.model.const_value(y) is None
            and ty == tr.type_of(a)
            and not ty.is_matrix
            and not tc.is_matrix
            and (tc.is_scalar or tc == ty)
        ):
            return y, c
    return None


def _evaluate(
    tr: FoldEmitter,
    call: A.Call,
    fn: Symbol,
    mask: str | None,
    constants: bool,
    chained: Any = None,
) -> tuple:
    """The call evaluated with its arguments bound to stand-in parameters: (the evaluation,
    the parameters' final terms by symbol id, the parameter symbols, the result's terms, the
    arguments read at run time as (index, node)); `constants`: the arguments' constant
    components as constants, else every argument a run-time value. Raises _Refuse."""
    ev = _Eval(tr, mask)
    ev.slots, ev.chained = len(call.args), chained
    known = known_globals(tr, call)
    ev.globals = {k: [_k(v) for v in vs] for k, vs in (known or {}).items()}
    ev.unknown = known is not None
    env: dict[int, list] = {}
    holders = ev.holders
    args = _argument_terms(tr, ev, call, fn, constants, holders, list(range(len(call.args))))
    params = [tr.model.symbol_of(p) for p in fn.node.proto.params]
    if any(p is None for p in params):
        raise _Refuse
    for p, v in zip(params, args):
        env[id(p)] = v
    result = ev.body(fn, env)
    if ev.unknown and _reads_unknown(
        [result] + [env[id(p)] for p, (_, _, d) in zip(params, fn.params) if d != "in"]
    ):
        raise _Refuse
    if constants:
        outs = [id(p) for p, (_, _, dr) in zip(params, fn.params) if dr != "in"]
        result, *written = ev.sunk([result] + [env[k] for k in outs])
        env.update(zip(outs, written))
    return ev, env, params, result, holders


def _argument_terms(
    tr: FoldEmitter,
    ev: _Eval,
    call: A.Call,
    fn: Symbol,
    constants: bool,
    holders: list[tuple[int, Any]],
    slots: list[int],
    source_of: A.Call | None = None,
) -> list[list[Any]]:
    """Per argument of `call` (of `fn`), its components' terms (None: an out parameter's,
    unknown); an argument read at run time is added to `holders` as (its slot, the node). A
    struct argument is a local the value of a call of a user function initialises
    (:func:`.call_sites.struct_source`): that call is evaluated here, its own arguments in new slots
    (`source_of`: the call they are then read at)."""
    args: list[list[Any]] = []
    for a, (_, _, dr), i in zip(call.args, fn.params, slots):
        t = tr.type_of(a)
        if t.is_struct and dr == "in":
            source = struct_source(tr, a, call)
            inner = tr.model.call_target(source) if source is not None else None
            if (
                source is None
                or not isinstance(inner, Symbol)
                or any(d != "in" for _, _, d in inner.params)
            ):
                raise _Refuse
            more = list(range(ev.slots, ev.slots + len(source.args)))
            ev.slots += len(source.args)
            values = _argument_terms(tr, ev, source, inner, constants, holders, more, call)
            args.append(ev.bound_call(inner, values))
            continue
        if t.is_array or t.is_struct or t.base != "float":
            raise _Refuse
        if dr == "out":
            args.append([None] * _width(t))
            continue
        cv = tr.model.const_value(a) if constants else None
        if cv is not None:
            args.append([_k(v, True) for v in _flat(cv)])
            continue
        scaled = (
            _scaled_argument(tr, a, call)
            if constants and (source_of is None or not isinstance(a, A.Identifier))
            else None
        )  # (a local's initializer read at another call than its own: not followed)
        if (
            scaled is not None
        ):  # y * #c: each component a product by the constant (NIR merges into it)
            y, c = scaled
            holders.append((i, y))
            cs = [_k(v, True) for v in _flat(tr.model.const_value(c))]
            args.append(
                [
                    _T("*", (x, cs[0] if len(cs) == 1 else cs[j]))
                    for j, x in enumerate(_leaves(f"@{i}@", t))
                ]
            )
            continue
        known = _constant_components(tr, a, call) if constants else None
        leaves = _leaves(f"@{i}@", t)
        holders.append((i, a))
        args.append(
            [k if k is not None else x for k, x in zip(known or [None] * len(leaves), leaves)]
        )
    return args


def out_roots(tr: FoldEmitter, call: A.Call, sym: Symbol | None) -> set[str] | None:
    """The operations at the root of each component of the value `call` (a call of a user
    function in the current function) writes into the variable `sym` passed whole as an out
    or inout argument, as NIR sees them after inlining: "+" (a sum), "*", "/", "neg", "call"
    (a built-in), "x" (an argument read as it is), "k" (a constant); None when the callee is
    not of the shape evaluated here (for nir_fold, which asks what a rule would look into)."""
    fn = tr.model.call_target(call)
    if not isinstance(fn, Symbol):
        return None
    memo = tr.fold_state.call_fold_roots
    key = (id(call), id(sym))
    if key not in memo:
        memo[key] = None
        try:
            _, env, params, _, _ = _evaluate(tr, call, fn, None, True)
        except _Refuse:
            return None
        for a, p, (_, _, dr) in zip(call.args, params, fn.params):
            if dr != "in" and isinstance(a, A.Identifier) and tr.model.symbol_of(a) is sym:
                memo[key] = {"k" if t.const else t.op for t in env[id(p)]}
    return memo[key]


def _product_sum(t: _T) -> bool:
    """The term is ``p1 + p2`` of two run-time products (or negated products: fneg(fmul) is
    fused as fmul of a negated factor)."""
    return t.op == "+" and all(
        (x.args[0] if x.op == "neg" else x).op == "*" and not x.const for x in t.args
    )


def record_sums(tr: FoldEngine, call: A.Call, arg: Any, terms: list, memo: dict) -> None:
    """Where the folded call `call` writes the variable `arg` (an out argument), the code of
    the two products each of its components sums (`memo`: a term's id -> its code), for
    :func:`product_sums`; read where the call was emitted (`tr.lines`)."""
    if isinstance(arg, A.Identifier):
        tr.fold_state.call_fold_sums[(id(call), id(tr.model.symbol_of(arg)))] = (
            [tuple(memo[id(x)] for x in t.args) if _product_sum(t) else None for t in terms],
            tr.lines,
        )


def product_sums(
    tr: FoldEngine, call: A.Call, sym: Symbol | None
) -> list[tuple[str, str] | None] | None:
    """Per component of the value the folded call `call` (written by an engine in the current
    Python function: :func:`record_sums`) wrote into the variable `sym`: the code of its two
    products when it is ``p1 + p2`` to NIR, else None; None when the call was not folded here.
    For nir_fold's ``(p1 + p2) + e -> (p1 + e) + p2``, read in llvmpipe mode only: the codes
    are temporaries of the ``if rt.lp:`` branch."""
    found = tr.fold_state.call_fold_sums.get((id(call), id(sym)))
    if found is None or found[1] is not tr.lines:
        return None  # (not folded, or folded in another Python function: an outlined part)
    return found[0]


_UNKNOWN = _T("x", code="@global@")  # a global's value where it is not known (_Eval.unknown)


def _float_global(sym: Symbol) -> bool:
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


def _reads_unknown(outs: list[list]) -> bool:
    """Some term of `outs` reads a global's unknown value."""
    seen: set[int] = set()
    todo = [t for terms in outs for t in terms if t is not None]
    while todo:
        t = todo.pop()
        if t is _UNKNOWN:
            return True
        if id(t) not in seen:
            seen.add(id(t))
            todo.extend(t.args)
    return False


def known_globals(tr: FoldEmitter, call: A.Call) -> dict[int, list[float]] | None:
    """The float globals whose values are compile-time constants where the entry point makes
    `call` (by symbol id, their components), as Mesa knows them after inlining every call: the
    entry has no caller, so its globals start at their constant initializers (zero without
    one), and a top-level statement before `call` that only calls straight-line functions
    (:meth:`_Eval.body`) leaves each global it writes at the constant those functions compute
    (``bump(); bump();`` with ``gCount += 1.0``). A global written under a branch or a loop, by
    a function this evaluation refuses, or from a run-time value is unknown from there on. Empty
    for a call in any other function, or under a branch or a loop of the entry: None."""
    f = tr.fn
    if f is None or not f.is_entry or f.sym is None:
        return None
    memo = tr.fold_state.call_fold_globals
    if memo is None:
        memo = tr.fold_state.call_fold_globals = _entry_globals(tr, f.sym)
    return memo.get(id(call))


def _entry_globals(tr: FoldEmitter, entry: Symbol) -> dict[int, dict[int, list[float]]]:
    """:func:`known_globals` for each call of a user function at the entry's top level."""
    state: dict[int, list[float]] = {}
    for sym in _globals(tr):
        t = sym.type
        init = sym.node.init if isinstance(sym.node, A.Declarator) else None
        if not _float_global(sym):
            continue
        cv = tr.model.const_value(init) if init is not None else None
        if init is None:
            state[id(sym)] = [0.0] * _size(t)
        elif cv is not None:
            state[id(sym)] = _flat(cv)
    found: dict[int, dict[int, list[float]]] = {}
    for st in entry.node.body.stmts:
        calls = _straight_calls(tr, st)
        if calls is None:
            _forget(tr, st, state)
            continue
        for c in calls:
            found[id(c)] = dict(state)
            _call_effect(tr, c, state)
        if isinstance(st, A.ExpressionStatement) and isinstance(st.expr, A.Assignment):
            a = st.expr
            g = tr.model.symbol_of(a.target) if isinstance(a.target, A.Identifier) else None
            if g is not None and id(g) in state:
                cv = tr.model.const_value(a.value) if a.op == "=" else None
                if cv is not None and len(_flat(cv)) == len(state[id(g)]):
                    state[id(g)] = _flat(cv)
                else:
                    del state[id(g)]
    return found


def _globals(tr: FoldEmitter) -> list[Symbol]:
    """The global variables the entry's calls may read or write."""
    seen: dict[int, Symbol] = {}
    for root in _reached(tr):
        for n in root.node.body.walk():
            if isinstance(n, A.Identifier):
                sym = tr.model.symbol_of(n)
                if sym is not None and sym.kind == "global" and sym.const_value is None:
                    seen[id(sym)] = sym
    return list(seen.values())


def _reached(tr: FoldEmitter) -> list[Symbol]:
    """The entry and the user functions it calls, through the functions they call."""
    assert tr.fn is not None and tr.fn.sym is not None
    out: dict[int, Symbol] = {}
    todo = [tr.fn.sym]
    while todo:
        fn = todo.pop()
        if id(fn) in out:
            continue
        out[id(fn)] = fn
        for n in fn.node.body.walk():
            if isinstance(n, A.Call) and isinstance(t := tr.model.call_target(n), Symbol):
                todo.append(t)
    return list(out.values())


def _straight_calls(tr: FoldEmitter, st: Any) -> list[A.Call] | None:
    """The calls of user functions of a declaration or expression statement of the entry, in the
    order they run (arguments first); None for any other statement, or one that writes a
    global other than as ``g = value;`` or chooses what runs (``?:``, ``&&``, ``||``)."""
    if isinstance(st, A.ExpressionStatement):
        root: Any = st.expr
    elif isinstance(st, A.DeclarationStatement) and isinstance(st.decl, A.VariableDeclaration):
        root = st.decl
    else:
        return None
    top = root.target if isinstance(root, A.Assignment) else None
    calls: list[A.Call] = []

    def visit(n: Any) -> bool:
        if isinstance(n, A.Ternary) or isinstance(n, A.Binary) and n.op in ("&&", "||"):
            return False
        for c in n.children():
            if not visit(c):
                return False
        for sym in tr.facts.written_variables(n):
            if sym.kind == "global" and not (n is root and top is not None):
                return False
        if isinstance(n, A.Call) and isinstance(tr.model.call_target(n), Symbol):
            calls.append(n)
        return True

    return calls if visit(root) else None


def _call_effect(tr: FoldEmitter, call: A.Call, state: dict[int, list[float]]) -> None:
    """`state` after `call`: the globals the callee writes at the constants it computes from
    `state`, or unknown."""
    fn = tr.model.call_target(call)
    written = tr.facts.global_effects(fn)[1]
    if not written:
        return
    ev = _Eval(tr, None)
    ev.slots = len(call.args)
    ev.globals = {k: [_k(v) for v in vs] for k, vs in state.items()}
    ev.unknown = True
    try:
        args = _argument_terms(tr, ev, call, fn, False, [], list(range(len(call.args))))
        params = [tr.model.symbol_of(p) for p in fn.node.proto.params]
        if any(p is None for p in params):
            raise _Refuse
        ev.body(fn, {id(p): v for p, v in zip(params, args)})
    except _Refuse:
        for k in written:
            state.pop(k, None)
        return
    for k in written:
        terms = ev.globals.get(k)
        if terms is not None and all(t.op == "k" and t.value is not None for t in terms):
            state[k] = [float(t.value) for t in terms]
        else:
            state.pop(k, None)


def _forget(tr: FoldEmitter, st: Any, state: dict[int, list[float]]) -> None:
    """Every global statement `st` may write (itself or through the functions it calls) is
    unknown from there on."""
    for n in st.walk():
        for sym in tr.facts.written_variables(n):
            state.pop(id(sym), None)
        if isinstance(n, A.Call) and isinstance(t := tr.model.call_target(n), Symbol):
            for k in tr.facts.global_effects(t)[1]:
                state.pop(k, None)
