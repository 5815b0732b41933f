"""Cross-check the NumPy runtime against llvmpipe (moderngl, EGL) on the hard numeric cases.

Each case is rendered as a 1x1 ``#version 300 es`` fragment shader whose inputs are uniforms
(so Mesa cannot constant-fold them) into an RGBA32I target; floats travel as
``floatBitsToInt`` so every bit, NaN included, comes back exactly. The test skips when no EGL
context can be created, unless the CI environment variable is set, in which case it fails.
"""

from __future__ import annotations

import numpy as np
import pytest

from glslcheck.backends import driver_profile
from glslcheck.backends.driver_profile import driver_model
from glslcheck.backends.numpy_engine.runtime import Runtime

NAN = float("nan")
INF = float("inf")


@pytest.fixture(scope="module")
def gl(gl):
    # the process-wide context of tests/conftest.py (glslcheck's own: it asks Mesa for WebGL's
    # zero initialisation, glsl_zero_init, which Mesa reads once per process at the first EGL
    # context), with this module's integer render on top; skipped or failed there as CI says
    ctx = gl
    vs = "#version 300 es\nin vec2 p; void main(){ gl_Position = vec4(p, 0.0, 1.0); }"
    vbo = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], dtype="f4").tobytes())

    def render(decl: str, body: str, uniforms: dict, size=(1, 1), textures=()):
        fs = (
            "#version 300 es\nprecision highp float;\nprecision highp int;\n"
            f"{decl}\nout ivec4 o;\nvoid main() {{ o = ivec4(0); {body} }}\n"
        )
        prog = ctx.program(vertex_shader=vs, fragment_shader=fs)
        for k, v in uniforms.items():
            if k in prog:
                prog[k].value = v
        for unit, (name, tex) in enumerate(textures):
            if name in prog:
                prog[name].value = unit
                tex.use(unit)
        vao = ctx.simple_vertex_array(prog, vbo, "p")
        tex = ctx.texture(size, 4, dtype="i4")
        fbo = ctx.framebuffer([tex])
        fbo.use()
        fbo.viewport = (0, 0) + tuple(size)
        vao.render()
        out = np.frombuffer(fbo.read(components=4, dtype="i4"), dtype="<i4").reshape(-1, 4)
        for obj in (vao, fbo, tex, prog):
            obj.release()
        return out

    render.ctx = ctx
    yield render
    vbo.release()  # the context is the process's, released by no test


RT = Runtime("float32")
F = RT.const_float
I = RT.const_int
U = RT.const_uint
UNIF = (
    "uniform float a; uniform float b; uniform float c; uniform int i; uniform int j;"
    " uniform uint u; uniform uint v;"
)

# (id, GLSL float expression, uniforms, runtime function of the same uniforms)
FLOAT_CASES = [
    ("pow(-2,2)", "pow(a, b)", dict(a=-2.0, b=2.0), lambda a, b: RT.pow(a, b)),
    ("pow(0,0)", "pow(a, b)", dict(a=0.0, b=0.0), lambda a, b: RT.pow(a, b)),
    ("pow(0,-1)", "pow(a, b)", dict(a=0.0, b=-1.0), lambda a, b: RT.pow(a, b)),
    ("pow(nan,1)", "pow(a, b)", dict(a=NAN, b=1.0), lambda a, b: RT.pow(a, b)),
    ("pow(inf,0)", "pow(a, b)", dict(a=INF, b=0.0), lambda a, b: RT.pow(a, b)),
    ("pow(1,inf)", "pow(a, b)", dict(a=1.0, b=INF), lambda a, b: RT.pow(a, b)),
    (
        "normalize(vec3(0))",
        "normalize(vec3(a)).x",
        dict(a=0.0),
        lambda a: RT.normalize(RT.vec(3, a))[0],
    ),
    ("normalize(0.0)", "normalize(a)", dict(a=0.0), lambda a: RT.normalize(a)),
    ("sqrt(-1)", "sqrt(a)", dict(a=-1.0), lambda a: RT.sqrt(a)),
    ("log(0)", "log(a)", dict(a=0.0), lambda a: RT.log(a)),
    ("log(-1)", "log(a)", dict(a=-1.0), lambda a: RT.log(a)),
    ("log2(0)", "log2(a)", dict(a=0.0), lambda a: RT.log2(a)),
    ("inversesqrt(0)", "inversesqrt(a)", dict(a=0.0), lambda a: RT.inversesqrt(a)),
    (
        "smoothstep(1,1,0.5)",
        "smoothstep(a, b, c)",
        dict(a=1.0, b=1.0, c=0.5),
        lambda a, b, c: RT.smoothstep(a, b, c),
    ),
    (
        "smoothstep(1,1,1)",
        "smoothstep(a, b, c)",
        dict(a=1.0, b=1.0, c=1.0),
        lambda a, b, c: RT.smoothstep(a, b, c),
    ),
    (
        "smoothstep(1,1,2)",
        "smoothstep(a, b, c)",
        dict(a=1.0, b=1.0, c=2.0),
        lambda a, b, c: RT.smoothstep(a, b, c),
    ),
    (
        "smoothstep(2,1,1.5)",
        "smoothstep(a, b, c)",
        dict(a=2.0, b=1.0, c=1.5),
        lambda a, b, c: RT.smoothstep(a, b, c),
    ),
    ("mod(-7.5,2)", "mod(a, b)", dict(a=-7.5, b=2.0), lambda a, b: RT.mod(a, b)),
    ("mod(1,0)", "mod(a, b)", dict(a=1.0, b=0.0), lambda a, b: RT.mod(a, b)),
    (
        "clamp(0.5,1,0)",
        "clamp(a, b, c)",
        dict(a=0.5, b=1.0, c=0.0),
        lambda a, b, c: RT.clamp(a, b, c),
    ),
    (
        "clamp(nan,0,1)",
        "clamp(a, b, c)",
        dict(a=NAN, b=0.0, c=1.0),
        lambda a, b, c: RT.clamp(a, b, c),
    ),
    ("min(nan,1)", "min(a, b)", dict(a=NAN, b=1.0), lambda a, b: RT.min_(a, b)),
    ("max(1,nan)", "max(a, b)", dict(a=1.0, b=NAN), lambda a, b: RT.max_(a, b)),
    ("round(2.5)", "round(a)", dict(a=2.5), lambda a: RT.round(a)),
    ("round(-2.5)", "round(a)", dict(a=-2.5), lambda a: RT.round(a)),
    ("round(0.5)", "round(a)", dict(a=0.5), lambda a: RT.round(a)),
    ("roundEven(2.5)", "roundEven(a)", dict(a=2.5), lambda a: RT.roundEven(a)),
    ("roundEven(-2.5)", "roundEven(a)", dict(a=-2.5), lambda a: RT.roundEven(a)),
    ("1e38*10", "a * b", dict(a=1e38, b=10.0), lambda a, b: RT.mul(a, b)),
    ("0*inf", "a * b", dict(a=0.0, b=INF), lambda a, b: RT.mul(a, b)),
    ("0/0", "a / b", dict(a=0.0, b=0.0), lambda a, b: RT.div(a, b)),
    ("atan(0,0)", "atan(a, b)", dict(a=0.0, b=0.0), lambda a, b: RT.atan(a, b)),
    ("atan(0,-0)", "atan(a, b)", dict(a=0.0, b=-0.0), lambda a, b: RT.atan(a, b)),
    ("atan(-0,-1)", "atan(a, b)", dict(a=-0.0, b=-1.0), lambda a, b: RT.atan(a, b)),
    ("atan(1,0)", "atan(a, b)", dict(a=1.0, b=0.0), lambda a, b: RT.atan(a, b)),
    ("atan(-1,0)", "atan(a, b)", dict(a=-1.0, b=0.0), lambda a, b: RT.atan(a, b)),
    ("atan(inf)", "atan(a)", dict(a=INF), lambda a: RT.atan(a)),
    ("fract(-0.25)", "fract(a)", dict(a=-0.25), lambda a: RT.fract(a)),
    ("fract(-1e-9)", "fract(a)", dict(a=-1e-9), lambda a: RT.fract(a)),
    ("fract(inf)", "fract(a)", dict(a=INF), lambda a: RT.fract(a)),
    ("sign(-0.0)", "sign(a)", dict(a=-0.0), lambda a: RT.sign(a)),
    ("sign(nan)", "sign(a)", dict(a=NAN), lambda a: RT.sign(a)),
    ("step(0,nan)", "step(a, b)", dict(a=0.0, b=NAN), lambda a, b: RT.step(a, b)),
    ("tanh(100)", "tanh(a)", dict(a=100.0), lambda a: RT.tanh(a)),
    ("tanh(-100)", "tanh(a)", dict(a=-100.0), lambda a: RT.tanh(a)),
    ("sinh(100)", "sinh(a)", dict(a=100.0), lambda a: RT.sinh(a)),
    ("asin(2)", "asin(a)", dict(a=2.0), lambda a: RT.asin(a)),
    ("asin(1)", "asin(a)", dict(a=1.0), lambda a: RT.asin(a)),
    ("acos(-1)", "acos(a)", dict(a=-1.0), lambda a: RT.acos(a)),
    ("acosh(0.5)", "acosh(a)", dict(a=0.5), lambda a: RT.acosh(a)),
    ("atanh(1)", "atanh(a)", dict(a=1.0), lambda a: RT.atanh(a)),
    ("floor(-0.5)", "floor(a)", dict(a=-0.5), lambda a: RT.floor(a)),
    ("ceil(-0.5)", "ceil(a)", dict(a=-0.5), lambda a: RT.ceil(a)),
    ("trunc(-0.5)", "trunc(a)", dict(a=-0.5), lambda a: RT.trunc(a)),
    ("abs(-0.0)", "abs(a)", dict(a=-0.0), lambda a: RT.abs(a)),
    ("mix(inf,1,1)", "mix(a, b, c)", dict(a=INF, b=1.0, c=1.0), lambda a, b, c: RT.mix(a, b, c)),
    ("modf(-2.5)", "modf(a, c)", dict(a=-2.5), lambda a: RT.modf(a)[0]),
    (
        "unpackSnorm(0x8000)",
        "unpackSnorm2x16(u).x",
        dict(u=0x8000),
        lambda u: RT.unpackSnorm2x16(u)[0],
    ),
    ("unpackHalf(nan)", "unpackHalf2x16(u).x", dict(u=0x7E00), lambda u: RT.unpackHalf2x16(u)[0]),
    (
        "intBitsToFloat(nan payload)",
        "intBitsToFloat(i)",
        dict(i=0x7FC00001),
        lambda i: RT.intBitsToFloat(i),
    ),
]

INT_CASES = [
    ("int(-7)/2", "i / j", dict(i=-7, j=2), lambda i, j: RT.div(i, j)),
    ("-7%2", "i % j", dict(i=-7, j=2), lambda i, j: RT.rem(i, j)),
    ("7%-2", "i % j", dict(i=7, j=-2), lambda i, j: RT.rem(i, j)),
    ("-7%-3", "i % j", dict(i=-7, j=-3), lambda i, j: RT.rem(i, j)),
    ("7%3", "i % j", dict(i=7, j=3), lambda i, j: RT.rem(i, j)),
    ("7%0", "i % j", dict(i=7, j=0), lambda i, j: RT.rem(i, j)),
    ("7/0", "i / j", dict(i=7, j=0), lambda i, j: RT.div(i, j)),
    ("-7/0", "i / j", dict(i=-7, j=0), lambda i, j: RT.div(i, j)),
    ("INT_MIN/-1", "i / j", dict(i=-(2**31), j=-1), lambda i, j: RT.div(i, j)),
    ("2147483647+1", "i + j", dict(i=2**31 - 1, j=1), lambda i, j: RT.add(i, j)),
    ("65536*65536", "i * j", dict(i=65536, j=65536), lambda i, j: RT.mul(i, j)),
    ("1<<32", "i << j", dict(i=1, j=32), lambda i, j: RT.shl(i, j)),
    ("1<<33", "i << j", dict(i=1, j=33), lambda i, j: RT.shl(i, j)),
    ("1<<-1", "i << j", dict(i=1, j=-1), lambda i, j: RT.shl(i, j)),
    ("-8>>1", "i >> j", dict(i=-8, j=1), lambda i, j: RT.shr(i, j)),
    ("-8>>33", "i >> j", dict(i=-8, j=33), lambda i, j: RT.shr(i, j)),
    ("abs(INT_MIN)", "abs(i)", dict(i=-(2**31)), lambda i: RT.abs(i)),
    ("uint 7/0", "int(u / v)", dict(u=7, v=0), lambda u, v: RT.to_int(RT.div(u, v))),
    ("uint 7%0", "int(u % v)", dict(u=7, v=0), lambda u, v: RT.to_int(RT.rem(u, v))),
    ("0u-1u", "int(u - v)", dict(u=0, v=1), lambda u, v: RT.to_int(RT.sub(u, v))),
    (
        "0x80000000u>>31",
        "int(u >> v)",
        dict(u=0x80000000, v=31),
        lambda u, v: RT.to_int(RT.shr(u, v)),
    ),
    (
        "0x80000000u>>32",
        "int(u >> v)",
        dict(u=0x80000000, v=32),
        lambda u, v: RT.to_int(RT.shr(u, v)),
    ),
] + [
    (f"int({x})", "int(a)", dict(a=x), lambda a: RT.to_int(a))
    for x in (3.99, -3.99, NAN, INF, -INF, 3e9, -3e9, 2147483520.0, -2147483648.0, -0.99)
]

# uint(x) of negative, NaN or huge x is undefined and llvmpipe's answer depends on the CPU
# (glslcheck/backends/driver_profile.py): the runtime is given the model measured on this driver, so
# these cases hold on every machine; tests/numpy/test_driver_profile.py checks each model on any
# machine.
UINT_INPUTS = (-0.5, -1.0, -3.5, 5e9, NAN, 3e9, 4294967040.0, INF, 2.7, 2147483648.0)


def _arg(name: str, value):
    if name in ("a", "b", "c"):
        return F(value)
    if name in ("i", "j"):
        return I(value)
    return U(value)


def _call(fn, uniforms):
    import inspect

    names = list(inspect.signature(fn).parameters)
    return fn(*(_arg(n, uniforms[n]) for n in names))


@pytest.mark.parametrize("case", FLOAT_CASES, ids=[c[0] for c in FLOAT_CASES])
def test_float_case_matches_llvmpipe(gl, case):
    _, expr, uniforms, fn = case
    body = f"o.x = floatBitsToInt({expr});"
    if expr.startswith("modf"):
        body = f"float ip; o.x = floatBitsToInt({expr.replace('c)', 'ip)')});"
    got = gl(UNIF, body, uniforms)[0, 0]
    with RT.errstate():
        ours = _call(fn, uniforms)
    ours = np.asarray(ours, dtype=np.float32).reshape(-1)[0]
    theirs = np.int32(got).view(np.float32)
    if np.isnan(theirs):
        assert np.isnan(ours), (expr, uniforms, theirs, ours)
    else:
        # exact bits (this also tells +0 from -0)
        assert np.float32(ours).view(np.int32) == np.int32(got), (expr, uniforms, theirs, ours)


@pytest.mark.parametrize("case", INT_CASES, ids=[c[0] for c in INT_CASES])
def test_int_case_matches_llvmpipe(gl, case):
    _, expr, uniforms, fn = case
    got = gl(UNIF, f"o.x = {expr};", uniforms)[0, 0]
    with RT.errstate():
        ours = np.asarray(_call(fn, uniforms)).reshape(-1)[0]
    assert ours.dtype == np.int32
    assert int(ours) == int(got), (expr, uniforms, int(got), int(ours))


def test_driver_follows_a_known_float_to_uint_model(gl):
    """The live driver is one of the models, and the one predicted from this CPU's flags (the
    NumPy backend's default when no driver is at hand, as in `glslcheck render`)."""
    model = driver_model(gl.ctx)
    assert model is not None, driver_profile.measure(gl.ctx)
    assert model == driver_profile.host_model()


@pytest.mark.parametrize("x", UINT_INPUTS, ids=[f"uint({x})" for x in UINT_INPUTS])
def test_uint_conversion_matches_llvmpipe(gl, x):
    rt = Runtime("float32", float_to_uint=driver_model(gl.ctx))
    got = gl(UNIF, "o.x = int(uint(a));", dict(a=x))[0, 0]
    with rt.errstate():
        ours = rt.to_int(rt.to_uint(F(x)))[0]
    assert int(ours) == int(got), (x, int(got), int(ours))


def test_constant_folded_remainder_is_c_remainder(gl):
    """Mesa folds % on constants with C semantics, unlike its run-time unsigned remainder."""
    got = gl("", "int a = -7; int b = 2; o.x = a % b; o.y = 7 % -2;", {})[0]
    assert int(RT.rem_const(I(-7), I(2))[0]) == got[0] == -1
    assert int(RT.rem_const(I(7), I(-2))[0]) == got[1] == 1


def _ulp(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ai = a.astype(np.float32).view(np.int32).astype(np.int64)
    bi = b.astype(np.float32).view(np.int32).astype(np.int64)
    ai = np.where(ai < 0, -(2**31) - ai, ai)
    bi = np.where(bi < 0, -(2**31) - bi, bi)
    return np.abs(ai - bi)


# (expression over per-pixel a, b; runtime function; max ULP distance to llvmpipe; input range)
# Bounds are what was measured on 4096 random inputs, rounded up: 0 where our formula is the
# one llvmpipe evaluates with correctly rounded steps; small where llvmpipe uses its own
# polynomial for a step (sin/cos ~1 ULP, exp2 3 ULP, NIR atan 3 ULP, Mesa asin/acos: the
# sqrt(1-|x|) factor amplifies 1-ULP differences near |x| = 1).
BULK = [
    ("a / b", lambda a, b: RT.div(a, b), 0, (-10, 10)),
    ("sqrt(abs(a))", lambda a, b: RT.sqrt(RT.abs(a)), 0, (-10, 10)),
    ("inversesqrt(abs(a))", lambda a, b: RT.inversesqrt(RT.abs(a)), 0, (-10, 10)),
    ("mod(a, b)", lambda a, b: RT.mod(a, b), 0, (-10, 10)),
    ("fract(a)", lambda a, b: RT.fract(a), 0, (-10, 10)),
    ("a * b + a", lambda a, b: RT.add(RT.mul(a, b), a), 0, (-10, 10)),
    ("length(vec2(a, b))", lambda a, b: RT.length(RT.vec(2, a, b)), 0, (-10, 10)),
    ("normalize(vec2(a, b)).y", lambda a, b: RT.normalize(RT.vec(2, a, b))[1], 0, (-10, 10)),
    # With a literal component Mesa/LLVM reassociate the dot product (x*x + (y*y + 1.0)), so
    # ~1% of results differ by 1-2 ULP from our left-to-right sum.
    (
        "normalize(vec3(a, b, 1.0)).y",
        lambda a, b: RT.normalize(RT.vec(3, a, b, 1.0))[1],
        2,
        (-10, 10),
    ),
    ("mix(a, b, 0.3)", lambda a, b: RT.mix(a, b, F(0.3)), 0, (-10, 10)),
    ("smoothstep(0.0, 1.0, a)", lambda a, b: RT.smoothstep(F(0.0), F(1.0), a), 0, (-1, 2)),
    (
        "cross(vec3(a, b, 1.0), vec3(b, 1.5, a)).x",
        lambda a, b: RT.cross(RT.vec(3, a, b, 1.0), RT.vec(3, b, 1.5, a))[0],
        0,
        (-10, 10),
    ),
    ("round(a)", lambda a, b: RT.round(RT.mul(RT.round(RT.mul(a, 2.0)), 0.5)), None, (-10, 10)),
    ("radians(a)", lambda a, b: RT.radians(a), 0, (-10, 10)),
    ("sin(a)", lambda a, b: RT.sin(a), 2, (-10, 10)),
    ("cos(a)", lambda a, b: RT.cos(a), 2, (-10, 10)),
    ("exp2(a)", lambda a, b: RT.exp2(a), 4, (-10, 10)),
    ("atan(a)", lambda a, b: RT.atan(a), 4, (-10, 10)),
    ("atan(a, b)", lambda a, b: RT.atan(a, b), 4, (-10, 10)),
    ("asin(a)", lambda a, b: RT.asin(a), 256, (-1, 1)),
    ("acos(a)", lambda a, b: RT.acos(a), 32, (-1, 1)),
]


@pytest.mark.parametrize("case", BULK, ids=[c[0] for c in BULK])
def test_bulk_random_inputs_against_llvmpipe(gl, case):
    expr, fn, max_ulp, (lo, hi) = case
    w, h = 64, 64
    rng = np.random.default_rng(1234)
    a = rng.uniform(lo, hi, w * h).astype(np.float32)
    b = rng.uniform(lo, hi, w * h).astype(np.float32)
    if expr == "round(a)":
        a = np.round(a * 2) / 2  # half-way cases
        expr, fn, max_ulp = "round(a)", (lambda a_, b_: RT.round(a_)), 0
    ctx = gl.ctx
    ta = ctx.texture((w, h), 1, a.tobytes(), dtype="f4")
    tb = ctx.texture((w, h), 1, b.tobytes(), dtype="f4")
    decl = "uniform highp sampler2D A; uniform highp sampler2D B;"
    body = (
        "ivec2 q = ivec2(gl_FragCoord.xy); float a = texelFetch(A, q, 0).x;"
        f" float b = texelFetch(B, q, 0).x; o.x = floatBitsToInt({expr});"
    )
    got = gl(decl, body, {}, size=(w, h), textures=(("A", ta), ("B", tb)))[:, 0].view(np.float32)
    ta.release()
    tb.release()
    with RT.errstate():
        ours = np.asarray(fn(a, b), dtype=np.float32)
    assert ours.dtype == np.float32
    both_nan = np.isnan(ours) & np.isnan(got)
    u = np.where(both_nan, 0, _ulp(ours, got))
    assert u.max() <= max_ulp, (expr, int(u.max()), float(np.mean(u == 0)))


def test_derivatives_match_llvmpipe_fine_quads(gl):
    w = h = 6
    decl = ""
    v = "float v = p.x * p.x * p.x + 100.0 * p.y * p.y * p.y + 10.0 * p.x * p.y;"
    res = gl(
        decl,
        f"vec2 p = gl_FragCoord.xy; {v} o.x = floatBitsToInt(v);"
        " o.y = floatBitsToInt(dFdx(v)); o.z = floatBitsToInt(dFdy(v));"
        " o.w = floatBitsToInt(fwidth(v));",
        {},
        size=(w, h),
    )
    vals = res.view(np.float32)
    ours_v = vals[:, 0]  # lane = y * w + x, y from the bottom: what the GL readback gives
    np.testing.assert_array_equal(RT.dFdx(ours_v, w), vals[:, 1])
    np.testing.assert_array_equal(RT.dFdy(ours_v, w), vals[:, 2])
    np.testing.assert_array_equal(RT.fwidth(ours_v, w), vals[:, 3])
