"""Built-in function calls of the compiled engine: each component as the NumPy runtime
computes it (runtime.Runtime's method of the same name), with Mesa's compile-time rewrites of
`pow` and nir_lower_flrp's choice of formula for `mix`
(backends/cpu_core/nir_fold.mix_form)."""

from __future__ import annotations

import math
from typing import Any

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ..cpu_core import nir_fold
from .ray_dots import ray_dot_val, ray_normalize
from .values import Val, broadcast_const, engine_error, not_yet

# one float32 component -> scalar.py function of the same rule (fma: llvmpipe's fused steps)
_UNARY_FMA = (
    "sin",
    "cos",
    "tan",
    "exp",
    "log",
    "exp2",
    "log2",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
)
_UNARY = {
    "asin": "asin",
    "acos": "acos",
    "sign": "sign",
    "fract": "fract",
    "inversesqrt": "inversesqrt",
    "sqrt": "np.sqrt",
    "floor": "np.floor",
    "ceil": "np.ceil",
    "trunc": "np.trunc",
    "round": "np.rint",
    "roundEven": "np.rint",
    "abs": "np.abs",
}
_RELATIONAL = {
    "lessThan": "<",
    "lessThanEqual": "<=",
    "greaterThan": ">",
    "greaterThanEqual": ">=",
    "equal": "==",
    "notEqual": "!=",
}


def builtin_call(cg: Any, e: A.Call, ov: Any) -> Val:
    name = ov.name
    if getattr(ov, "category", None) == B.TEXTURE or name.startswith(("texture", "texel")):
        from .texture_calls import texture_call

        return texture_call(cg, e, name)
    rtype = cg.type_of(e)
    if name in ("dFdx", "dFdy", "fwidth"):
        # Placeholders the lockstep rewrite replaces by differences between a quad's lanes
        # (lanes.py `dfdx`); a per-pixel module holding them is never compiled (engine.generate).
        if cg.derivative is None:
            cg.derivative = e
        x = []
        for p in cg.expr(e.args[0]).parts:  # each leaf a name: the rewrite reads its lanes
            x.append(p if p.isidentifier() else cg.tmp_fresh(p))
        form = {"dFdx": "dfdx({})", "dFdy": "dfdy({})"}.get(
            name, "(np.abs(dfdx({0})) + np.abs(dfdy({0})))"
        )
        # into fresh temporaries: every lane reads its quad's lanes before any is written (`x =
        # dFdx(x)`)
        return Val(rtype, [cg.tmp_fresh(form.format(p)) for p in x])
    if name == "modf":
        x = cg.expr(e.args[0])
        targets = cg.lvalue(e.args[1])
        ip = [cg.tmp(f"np.trunc({p})") for p in x.parts]
        fr = [cg.tmp(f"({p} - {i})") for p, i in zip(x.parts, ip)]
        cg.write(targets, ip)
        return Val(rtype, fr)
    args = [cg.expr(a) for a in e.args]
    base = args[0].t.base if args else None
    n = max((len(a.parts) for a in args), default=1)

    def comps(v: Val) -> list[str]:
        """v's components, a scalar repeated for a vector call (atomised: read n times)."""
        if len(v.parts) == n:
            return v.parts
        return [cg.atom(v.parts[0])] * n

    def each(fn) -> Val:
        cols = [comps(a) for a in args]
        return Val(rtype, [fn(*xs) for xs in zip(*cols)])

    if name == "exp" and base == "float" and cg.fn is not None and cg.fn.sym is not None:
        lowered = nir_fold.exp_product(cg.fold_context(), e, args, None)  # exp2(x * (k*log2(e)))
        if lowered is not None:
            return lowered
    if base == "float" and componentwise_text(cg, name, "x") is not None:
        return each(lambda x: componentwise_text(cg, name, x))
    if name == "atan":
        if len(args) == 1:
            return each(lambda y: f"atan({y})")
        return each(lambda y, x: f"atan2({y}, {x})")
    if name == "abs" and base == "int":
        return each(lambda x: f"iabs({x})")
    if name == "sign" and base == "int":
        return each(lambda x: f"isign({x})")
    if name == "pow":
        return pow_call(cg, e, args, rtype, n)
    if name in ("min", "max"):
        if base == "float":
            return each(lambda a, b: f"f{name}({a}, {b})")
        cast = "I32" if base == "int" else "U32"
        return each(lambda a, b: f"{cast}({name}({a}, {b}))")
    if name == "clamp":
        if base == "float":
            return each(lambda x, lo, hi: f"clamp({x}, {lo}, {hi})")
        cast = "I32" if base == "int" else "U32"
        return each(lambda x, lo, hi: f"{cast}(min(max({x}, {lo}), {hi}))")
    if name == "mod":
        return each(lambda x, y: f"mod({x}, {y})")
    if name == "step":
        return each(lambda edge, x: f"step({edge}, {x})")
    if name == "smoothstep":
        return each(lambda a, b, x: f"smoothstep({a}, {b}, {x})")
    if name == "mix":
        return mix_call(cg, e, args, rtype, n, comps)
    if name == "isnan":
        return each(lambda x: f"({x} != {x})")
    if name == "isinf":
        return each(lambda x: f"np.isinf({x})")
    if name in ("floatBitsToInt", "floatBitsToUint", "intBitsToFloat", "uintBitsToFloat"):
        fn = {
            "floatBitsToInt": "float_bits_to_int",
            "floatBitsToUint": "float_bits_to_uint",
            "intBitsToFloat": "int_bits_to_float",
            "uintBitsToFloat": "uint_bits_to_float",
        }[name]
        return each(lambda x: f"{fn}({x})")
    if name in _RELATIONAL:
        op = _RELATIONAL[name]
        return each(lambda a, b: f"({a} {op} {b})")
    if name == "any":
        return Val(rtype, ["(" + " or ".join(args[0].parts) + ")"])
    if name == "all":
        return Val(rtype, ["(" + " and ".join(args[0].parts) + ")"])
    if name == "not":
        return each(lambda x: f"(not {x})")
    if name == "dot" and cg.fn is not None and cg.fn.sym is not None:
        fold = cg.fold_context()  # constants merged into a dot product, dot(vec2(s), #K)
        merged = nir_fold.merged_dot(fold, e, args, None)
        if merged is None:
            merged = nir_fold.broadcast_dot(fold, e, args, None)
        if nir_fold.ray_dot(fold, e) is not None:  # a caller's ray's constants merged
            written = merged if merged is not None else geometric(cg, name, args, rtype)
            return ray_dot_val(cg, e, args, written)
        if merged is not None:
            return merged
    if name == "normalize":
        kept = ray_normalize(cg, e, args, rtype)  # a ray root's rsq kept (nir_fold.ray_dots)
        if kept is not None:
            return kept
    if name in (
        "dot",
        "length",
        "distance",
        "normalize",
        "cross",
        "reflect",
        "refract",
        "faceforward",
    ):
        return geometric(cg, name, args, rtype)
    if name == "matrixCompMult":
        return each(lambda a, b: f"({a} * {b})")
    if name == "transpose":
        m = args[0]
        c, r = m.t.cols, m.t.rows
        return Val(rtype, [m.parts[j * r + i] for i in range(r) for j in range(c)])
    if name == "outerProduct":
        c = [cg.atom(p) for p in args[0].parts]
        r = [cg.atom(p) for p in args[1].parts]
        return Val(rtype, [f"({cj} * {ri})" for ri in r for cj in c])
    if name == "determinant":
        return Val(rtype, [determinant(cg, [cg.atom(p) for p in args[0].parts], args[0].t.cols)])
    if name == "inverse" and args[0].t.cols == 2:
        m = [cg.atom(p) for p in args[0].parts]
        det = cg.tmp(determinant(cg, m, 2))
        adj = [m[3], f"(-{m[1]})", f"(-{m[2]})", m[0]]
        return Val(rtype, [f"({a} / {det})" for a in adj])
    raise not_yet(f"the built-in {name}()", e)


def componentwise_text(cg: Any, name: str, x: str) -> Any:
    """The float built-in `name` of one component x (the Runtime's method of that name), or None
    for a built-in that is not computed component by component from one argument."""
    if name in _UNARY_FMA:
        return f"{name}({x}, FMA)"  # (fma: llvmpipe's fused steps)
    if name in _UNARY:
        return f"{_UNARY[name]}({x})"
    if name in ("radians", "degrees"):
        k = cg.cf(math.pi / 180.0 if name == "radians" else 180.0 / math.pi)
        return f"({x} * {k})"
    return None


def pow_call(cg: Any, e: A.Call, args: list[Val], rtype: Any, n: int) -> Val:
    """Mesa's rewrites (transpile.Expressions.pow_rewrite, Runtime.pow_const): a constant base
    of ones is 1, of twos exp2(y); a constant exponent component of 1.0, 2.0, 4.0 or +0.0 is
    x, x*x, (x*x)*(x*x), or 1 (0 for x 0 or NaN) when some component is one of them; else the
    run-time pow."""
    x, y = args
    xs = x.parts if len(x.parts) == n else [cg.atom(x.parts[0])] * n
    ys = y.parts if len(y.parts) == n else [cg.atom(y.parts[0])] * n
    if x.const is not None and all(v == 1.0 for v in x.const):
        return Val(rtype, [cg.cf(1.0)] * n)
    if x.const is not None and all(v == 2.0 for v in x.const):
        return Val(rtype, [f"exp2({p}, FMA)" for p in ys])
    c = broadcast_const(y.const, n)
    special = c is not None and any(
        v in (1.0, 2.0, 4.0) or (v == 0.0 and math.copysign(1.0, v) > 0) for v in c
    )
    consts = c if c is not None else []  # (read only when special: c is not None)
    out = []
    for i in range(n):
        if special:
            v = float(consts[i])
            if v == 1.0:
                out.append(xs[i])
                continue
            if v == 2.0:
                a = cg.atom(xs[i])
                out.append(f"({a} * {a})")
                continue
            if v == 4.0:
                a = cg.atom(xs[i])
                sq = cg.tmp(f"({a} * {a})")
                out.append(f"({sq} * {sq})")
                continue
            if v == 0.0 and math.copysign(1.0, v) > 0:
                out.append(f"pow_zero({xs[i]})")
                continue
        out.append(f"pow({xs[i]}, {ys[i]}, FMA)")
    if c is None and y.constlike and len(y.parts) <= 4:
        # Runtime.pow: an exponent the same in every lane (taken for a constant) whose
        # components are all 0, 1, 2 or 4 (no -0.0) is rewritten as Mesa does (pow_const); all
        # zeros give 1 everywhere
        ys = [cg.atom(p) for p in y.parts]
        special = cg.tmp(" and ".join(f"pow_special({p})" for p in ys))
        zeros = cg.tmp(" and ".join(f"({p} == F32(0.0))" for p in ys))
        yn = ys if len(ys) == n else ys * n
        out = [f"pow_uniform({p}, {q}, {special}, {zeros}, FMA)" for p, q in zip(xs, yn)]
    return Val(rtype, out)


def mix_call(cg: Any, e: A.Call, args: list[Val], rtype: Any, n: int, comps) -> Val:
    x, y, a = args
    if a.t.base == "bool":
        return Val(
            rtype, [f"({yy} if {aa} else {xx})" for xx, yy, aa in zip(comps(x), comps(y), comps(a))]
        )

    form = (
        nir_fold.mix_form(cg.fold_context(), e)
        if cg.fn is not None and cg.fn.sym is not None
        else None
    )
    if form is None:
        form = "strict" if a.const is not None else "fast"
    if isinstance(form, tuple):  # a form per component (nir_fold.mix_form)
        vals = {f: _mix_form(cg, f, x, y, a, rtype, comps) for f in dict.fromkeys(form)}
        return Val(rtype, [vals[f].parts[i] for i, f in enumerate(form)])
    return _mix_form(cg, form, x, y, a, rtype, comps)


def _mix_form(cg: Any, form: str, x: Val, y: Val, a: Val, rtype: Any, comps) -> Val:
    xs, ys, as_ = comps(x), comps(y), comps(a)
    if form == "select":  # a b2f weight: y where it is 1 (Runtime.mix)
        one = cg.cf(1.0)  # (the weight a name: a pure select, lsel in lockstep lanes)
        return Val(
            rtype, [f"({q} if {cg.atom(t)} == {one} else {p})" for p, q, t in zip(xs, ys, as_)]
        )
    if form == "fast":
        return Val(rtype, [f"mix_fast({p}, {q}, {t})" for p, q, t in zip(xs, ys, as_)])
    if form in ("one", "minus_one"):
        op = "-" if form == "one" else "+"
        out = []
        for p, q, t in zip(xs, ys, as_):
            t = cg.atom(t)
            out.append(f"(({p} {op} {t}) + ({q} * {t}))")
        return Val(rtype, out)
    # strict: fmul(x, 1 - a) + fmul(y, a), Mesa's constant-zero folding included
    one = cg.cf(1.0)
    at = Val(a.t, [cg.atom(p) for p in a.parts], a.const, a.uni)
    inv = Val(
        a.t, [f"({one} - {p})" for p in at.parts], None, a.constlike
    )  # Runtime.mix: self._1 - a
    if a.const is not None:
        inv.const = [float(_f32(1.0 - v)) for v in a.const]
    left = cg.fmul(x, inv, rtype)
    right = cg.fmul(y, at, rtype)
    return Val(rtype, [f"({p} + {q})" for p, q in zip(left.parts, right.parts)])


def _f32(v: float) -> float:
    import numpy as np

    return float(np.float32(v))


def geometric(cg: Any, name: str, args: list[Val], rtype: Any) -> Val:
    if name == "dot":
        a, b = args
        if len(a.parts) == 1:
            return cg.fmul(a, b, rtype)
        pa = [cg.atom(p) for p in a.parts]
        pb = [cg.atom(p) for p in b.parts]
        if a.constlike == b.constlike:
            return Val(rtype, [cg.dot_text(pa, pb)])
        # Runtime.dot: a constant zero component of the constant operand drops its product
        prods = cg.fmul(Val(a.t, pa, a.const, a.uni), Val(b.t, pb, b.const, b.uni), a.t).parts
        text = prods[-1]
        for i in range(len(prods) - 2, -1, -1):
            text = f"({prods[i]} + {text})"
        return Val(rtype, [text])
    if name in ("length", "distance"):
        if name == "distance":
            a, b = args
            parts = [cg.atom(f"({p} - {q})") for p, q in zip(a.parts, b.parts)]
        else:
            parts = [cg.atom(p) for p in args[0].parts]
        if len(parts) == 1:
            return Val(rtype, [f"np.abs({parts[0]})"])
        return Val(rtype, [f"np.sqrt({cg.dot_text(parts, parts)})"])
    if name == "normalize":
        parts = [cg.atom(p) for p in args[0].parts]
        if len(parts) == 1:
            return Val(rtype, [f"sign({parts[0]})"])
        d = cg.tmp(f"(F32(1.0) / np.sqrt({cg.dot_text(parts, parts)}))")
        return Val(rtype, [f"({p} * {d})" for p in parts])
    if name == "cross":
        pa = [cg.atom(p) for p in args[0].parts]
        pb = [cg.atom(p) for p in args[1].parts]
        return Val(
            rtype,
            [
                f"(({pa[1]} * {pb[2]}) - ({pa[2]} * {pb[1]}))",
                f"(({pa[2]} * {pb[0]}) - ({pa[0]} * {pb[2]}))",
                f"(({pa[0]} * {pb[1]}) - ({pa[1]} * {pb[0]}))",
            ],
        )
    if name == "reflect":  # i - 2 * (dot(n, i) * n)
        pi = [cg.atom(p) for p in args[0].parts]
        pn = [cg.atom(p) for p in args[1].parts]
        d = cg.tmp(cg.dot_text(pn, pi) if len(pi) > 1 else f"({pn[0]} * {pi[0]})")
        two = cg.cf(2.0)
        return Val(rtype, [f"({p} - ({two} * ({d} * {q})))" for p, q in zip(pi, pn)])
    if name == "refract":
        pi = [cg.atom(p) for p in args[0].parts]
        pn = [cg.atom(p) for p in args[1].parts]
        eta = cg.atom(args[2].parts[0])
        d = cg.tmp(cg.dot_text(pn, pi) if len(pi) > 1 else f"({pn[0]} * {pi[0]})")
        one = cg.cf(1.0)
        k = cg.tmp(f"({one} - (({eta} * {eta}) * ({one} - ({d} * {d}))))")
        f = cg.tmp(f"(({eta} * {d}) + np.sqrt({k}))")
        zero = cg.cf(0.0)
        return Val(
            rtype,
            [
                f"({zero} if {k} < {zero} else (({eta} * {p}) - ({f} * {q})))"
                for p, q in zip(pi, pn)
            ],
        )
    if name == "faceforward":
        vn, vi, nref = args
        pa = [cg.atom(p) for p in nref.parts]
        pb = [cg.atom(p) for p in vi.parts]
        c = cg.tmp(
            f"({cg.dot_text(pa, pb) if len(pa) > 1 else f'({pa[0]} * {pb[0]})'} < {cg.cf(0.0)})"
        )
        return Val(rtype, [f"({p} if {c} else (-{p}))" for p in [cg.atom(q) for q in vn.parts]])
    raise engine_error(f"{name}()", None)


def determinant(cg: Any, m: list[str], n: int) -> str:
    """Runtime.determinant: cofactor expansion along the first column (Mesa's built-in)."""

    def at(c: int, r: int) -> str:
        return m[c * n + r]

    if n == 2:
        return f"(({at(0, 0)} * {at(1, 1)}) - ({at(1, 0)} * {at(0, 1)}))"
    if n == 3:
        return (
            f"((({at(0, 0)} * (({at(1, 1)} * {at(2, 2)}) - ({at(2, 1)} * {at(1, 2)})))"
            f" - ({at(1, 0)} * (({at(0, 1)} * {at(2, 2)}) - ({at(2, 1)} * {at(0, 2)}))))"
            f" + ({at(2, 0)} * (({at(0, 1)} * {at(1, 2)}) - ({at(1, 1)} * {at(0, 2)}))))"
        )
    sf = [
        cg.tmp(t)
        for t in (
            f"(({at(2, 2)} * {at(3, 3)}) - ({at(3, 2)} * {at(2, 3)}))",
            f"(({at(2, 1)} * {at(3, 3)}) - ({at(3, 1)} * {at(2, 3)}))",
            f"(({at(2, 1)} * {at(3, 2)}) - ({at(3, 1)} * {at(2, 2)}))",
            f"(({at(2, 0)} * {at(3, 3)}) - ({at(3, 0)} * {at(2, 3)}))",
            f"(({at(2, 0)} * {at(3, 2)}) - ({at(3, 0)} * {at(2, 2)}))",
            f"(({at(2, 0)} * {at(3, 1)}) - ({at(3, 0)} * {at(2, 1)}))",
        )
    ]
    c0 = f"((({at(1, 1)} * {sf[0]}) - ({at(1, 2)} * {sf[1]})) + ({at(1, 3)} * {sf[2]}))"
    c1 = f"(-((({at(1, 0)} * {sf[0]}) - ({at(1, 2)} * {sf[3]})) + ({at(1, 3)} * {sf[4]})))"
    c2 = f"((({at(1, 0)} * {sf[1]}) - ({at(1, 1)} * {sf[3]})) + ({at(1, 3)} * {sf[5]}))"
    c3 = f"(-((({at(1, 0)} * {sf[2]}) - ({at(1, 1)} * {sf[4]})) + ({at(1, 2)} * {sf[5]})))"
    return (
        f"(((({at(0, 0)} * {c0}) + ({at(0, 1)} * {c1})) + ({at(0, 2)} * {c2}))"
        f" + ({at(0, 3)} * {c3}))"
    )
