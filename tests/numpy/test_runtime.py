"""Unit tests of the NumPy runtime: representation, operators, built-ins, masks, indexing."""

from __future__ import annotations

import math

import numpy as np
import pytest

from glslcheck.backends.numpy_engine.runtime import Runtime
from glslcheck.backends.numpy_engine.runtime_values import GLSLRuntimeError, Struct

RT = Runtime()
F, I, U, B = RT.const_float, RT.const_int, RT.const_uint, RT.const_bool
NAN = float("nan")


@pytest.fixture(autouse=True)
def _quiet():
    with RT.errstate():
        yield


def val(x):
    return np.asarray(x).reshape(-1)[0]


# ---------------------------------------------------------------- representation & constructors
def test_constants_have_lane_axis_and_dtype():
    assert F(1.5).shape == (1,) and F(1.5).dtype == np.float32
    assert I(3).dtype == np.int32 and U(3).dtype == np.uint32 and B(True).dtype == np.bool_
    assert val(I(2**31)) == -(2**31)  # literals wrap to 32 bits
    assert val(U(-1)) == 0xFFFFFFFF


def test_vec_constructor_flattens_and_splats():
    v = RT.vec(3, F(1.0), RT.vec(2, 2.0, 3.0))
    assert v.shape == (3, 1) and v.dtype == np.float32
    assert v[:, 0].tolist() == [1.0, 2.0, 3.0]
    assert RT.vec(4, F(2.0))[:, 0].tolist() == [2.0] * 4
    lanes = np.arange(5, dtype=np.float32)
    w = RT.vec(2, lanes, F(7.0))
    assert w.shape == (2, 5) and w[1].tolist() == [7.0] * 5
    # vec from a longer vector drops the rest; ivec truncates floats
    assert RT.vec(2, RT.vec(4, 1.0, 2.0, 3.0, 4.0))[:, 0].tolist() == [1.0, 2.0]
    assert RT.ivec(2, F(-3.7), F(3.7))[:, 0].tolist() == [-3, 3]
    assert RT.bvec(2, F(0.0), F(NAN))[:, 0].tolist() == [False, True]
    assert RT.vec(2, B(True), I(3))[:, 0].tolist() == [1.0, 3.0]


def test_mat_constructors():
    d = RT.mat(3, 3, F(2.0))
    assert d.shape == (3, 3, 1)
    np.testing.assert_array_equal(d[..., 0], 2 * np.eye(3))
    m = RT.mat(2, 2, 1.0, 2.0, 3.0, 4.0)  # column-major: m[0] = (1, 2)
    assert m[0, :, 0].tolist() == [1.0, 2.0] and m[1, :, 0].tolist() == [3.0, 4.0]
    big = RT.mat(4, 4, m)
    expect = np.eye(4)
    expect[:2, :2] = m[..., 0]
    np.testing.assert_array_equal(big[..., 0], expect)
    small = RT.mat(2, 3, RT.mat(4, 4, *range(16)))
    np.testing.assert_array_equal(small[..., 0], np.arange(16).reshape(4, 4)[:2, :3])
    assert RT.mat(2, 2, RT.vec(4, 1.0, 2.0, 3.0, 4.0))[1, 1, 0] == 4.0


def test_struct_and_arrays():
    s = RT.struct("Ray", o=RT.vec(3, 0.0), d=RT.vec(3, 1.0))
    assert isinstance(s, Struct) and s.type_name == "Ray"
    assert s.d[:, 0].tolist() == [1.0, 1.0, 1.0]
    with pytest.raises(AttributeError):
        s.o = 1
    t = RT.assign_field(s, "o", RT.vec(3, 5.0), np.array([True, False]))
    assert t.o.shape == (3, 2) and t.o[0].tolist() == [5.0, 0.0]
    assert s.o[0, 0] == 0.0  # the original is untouched: value semantics
    arr = RT.array(F(1.0), F(2.0), F(3.0))
    assert arr.shape == (3, 1)
    sa = RT.array(s, t)
    assert sa.o.shape == (2, 3, 2)
    assert RT.index(sa, 1).o[0].tolist() == [5.0, 0.0]


# ---------------------------------------------------------------- arithmetic
def test_broadcasting_scalar_vector_matrix():
    v = RT.vec(3, 1.0, 2.0, 3.0)
    assert RT.mul(F(2.0), v)[:, 0].tolist() == [2.0, 4.0, 6.0]
    assert RT.add(v, 1.0)[:, 0].tolist() == [2.0, 3.0, 4.0]
    m = RT.mat(2, 2, F(1.0))
    assert RT.mul(m, F(3.0))[..., 0].tolist() == [[3.0, 0.0], [0.0, 3.0]]


def test_matrix_products():
    m = RT.mat(2, 2, 1.0, 2.0, 3.0, 4.0)  # columns (1,2), (3,4): rows [1 3; 2 4]
    v = RT.vec(2, 1.0, 1.0)
    assert RT.mat_mul_vec(m, v)[:, 0].tolist() == [4.0, 6.0]
    assert RT.vec_mul_mat(v, m)[:, 0].tolist() == [3.0, 7.0]
    mm = RT.mat_mul_mat(m, m)
    np.testing.assert_array_equal(
        mm[..., 0].T, np.array([[1, 3], [2, 4]]) @ np.array([[1, 3], [2, 4]])
    )
    # non-square: mat3x2 (3 columns of vec2) * vec3 -> vec2
    m32 = RT.mat(3, 2, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
    assert RT.mat_mul_vec(m32, RT.vec(3, 1.0, 1.0, 1.0))[:, 0].tolist() == [9.0, 12.0]
    assert RT.mat_mul_mat(m32, RT.mat(2, 3, F(1.0))).shape == (2, 2, 1)
    np.testing.assert_array_equal(RT.transpose(m32)[..., 0], m32[..., 0].T)
    op = RT.outerProduct(RT.vec(2, 1.0, 2.0), RT.vec(3, 1.0, 10.0, 100.0))
    assert op.shape == (3, 2, 1) and op[2, 1, 0] == 200.0


def test_determinant_and_inverse_against_numpy():
    rng = np.random.default_rng(0)
    for n in (2, 3, 4):
        a = rng.uniform(-2, 2, (n, n)).astype(np.float32)
        m = RT.mat(n, n, *a.reshape(-1))  # column-major components: column c = a[c]
        assert abs(val(RT.determinant(m)) - np.linalg.det(a.astype(np.float64))) < 1e-4
        inv = RT.inverse(m)
        assert inv.dtype == np.float32
        np.testing.assert_allclose(RT.mat_mul_mat(m, inv)[..., 0], np.eye(n), atol=1e-4)


def test_int_division_truncates_and_wraps():
    a = np.array([-7, 7, -7, 7, 0, -(2**31)], dtype=np.int32)
    b = np.array([2, 2, -2, -2, 0, -1], dtype=np.int32)
    assert RT.div(a, b).tolist() == [-3, 3, 3, -3, 0, -(2**31)]
    assert RT.div(I(5), I(0)).tolist() == [0]
    assert RT.add(I(2**31 - 1), I(1)).tolist() == [-(2**31)]
    assert RT.mul(I(65536), I(65536)).tolist() == [0]
    assert RT.sub(I(-(2**31)), I(1)).tolist() == [2**31 - 1]
    assert RT.neg(I(-(2**31))).tolist() == [-(2**31)]
    assert RT.sub(U(0), U(1)).tolist() == [0xFFFFFFFF]
    assert RT.div(U(7), U(0)).tolist() == [0xFFFFFFFF]
    assert RT.div(U(7), U(2)).tolist() == [3]


def test_remainder_runtime_and_constant_forms():
    a = np.array([-7, 7, -7, 7, 7], dtype=np.int32)
    b = np.array([2, -2, -3, 3, 0], dtype=np.int32)
    assert RT.rem(a, b).tolist() == [1, 7, -7, 1, -1]  # llvmpipe: unsigned remainder of the bits
    assert RT.rem_const(a, b).tolist() == [-1, 1, -1, 1, -1]  # C remainder (folded constants)
    assert RT.rem(U(7), U(0)).tolist() == [0xFFFFFFFF]
    assert RT.rem(U(7), U(3)).dtype == np.uint32


def test_shifts_and_bits():
    assert RT.shl(I(1), I(31)).tolist() == [-(2**31)]
    assert RT.shl(I(1), I(32)).tolist() == [1]
    assert RT.shr(I(-8), I(1)).tolist() == [-4]
    assert RT.shr(U(0x80000000), U(31)).tolist() == [1]
    assert RT.shr(U(0x80000000), I(1)).tolist() == [0x40000000]  # logical for uint
    assert RT.shl(I(3), U(2)).tolist() == [12]  # mixed signedness count
    assert RT.bit_and(I(6), I(3)).tolist() == [2]
    assert RT.bit_or(I(6), I(3)).tolist() == [7]
    assert RT.bit_xor(I(6), I(3)).tolist() == [5]
    assert RT.bit_not(I(0)).tolist() == [-1]
    assert RT.bit_not(U(0)).tolist() == [0xFFFFFFFF]


def test_comparisons_and_logic():
    assert RT.lt(F(NAN), F(1.0)).tolist() == [False]
    assert RT.eq(F(NAN), F(NAN)).tolist() == [False]
    assert RT.ne(F(NAN), F(NAN)).tolist() == [True]
    a = RT.vec(3, 1.0, 2.0, 3.0)
    assert RT.equal_all(a, RT.vec(3, 1.0, 2.0, 3.0)).tolist() == [True]
    assert RT.nequal_all(a, RT.vec(3, 1.0, 2.0, 4.0)).tolist() == [True]
    s1 = RT.struct("S", a=F(1.0), b=I(2))
    s2 = RT.struct("S", a=F(1.0), b=I(3))
    assert RT.equal_all(s1, s1).tolist() == [True] and RT.equal_all(s1, s2).tolist() == [False]
    t, f = B(True), B(False)
    assert RT.and_(t, f).tolist() == [False] and RT.or_(t, f).tolist() == [True]
    assert RT.xor_(t, t).tolist() == [False] and RT.not_(f).tolist() == [True]
    bv = RT.lessThan(a, RT.vec(3, 2.0))
    assert bv[:, 0].tolist() == [True, False, False]
    assert val(RT.any(bv)) and not val(RT.all(bv))
    assert RT.not_vec(bv)[:, 0].tolist() == [False, True, True]


# ---------------------------------------------------------------- conversions
def test_float_to_int_and_uint_edges():
    x = np.array([3.99, -3.99, NAN, np.inf, -np.inf, 3e9, -3e9, -0.99], dtype=np.float32)
    assert RT.to_int(x).tolist() == [3, -3, -(2**31), -(2**31), -(2**31), -(2**31), -(2**31), 0]
    # uint(x) of negative, NaN and huge x: the CPU decides (test_driver_profile.py has the models)
    y = np.array([-0.5, -1.0, 3e9, 5e9, NAN, 2.7], dtype=np.float32)
    avx512 = Runtime("float32", float_to_uint="avx512")
    assert avx512.to_uint(y).tolist() == [0, 0xFFFFFFFF, 3000000000, 0xFFFFFFFF, 0xFFFFFFFF, 2]
    sse = Runtime("float32", float_to_uint="sse")
    assert sse.to_uint(y).tolist() == [0, 0xFFFFFFFF, 3000000000, 0x80000000, 0x80000000, 2]
    assert RT.to_int(U(0xFFFFFFFF)).tolist() == [-1]
    assert RT.to_uint(I(-1)).tolist() == [0xFFFFFFFF]
    assert RT.to_float(I(-3)).dtype == np.float32
    assert RT.to_bool(F(-0.0)).tolist() == [False]
    assert RT.to_float(B(True)).tolist() == [1.0]


# ---------------------------------------------------------------- masks and indexing
def test_assign_under_mask_broadcasts():
    old = F(1.0)
    new = np.array([5.0, 6.0, 7.0], dtype=np.float32)
    mask = np.array([True, False, True])
    assert RT.assign(old, new, mask).tolist() == [5.0, 1.0, 7.0]
    assert RT.assign(old, F(9.0), mask).tolist() == [9.0, 1.0, 9.0]
    assert RT.assign(old, F(9.0)).tolist() == [9.0]
    v = RT.vec(3, 0.0)
    out = RT.assign_swizzle(v, "zx", RT.vec(2, 1.0, 2.0), mask)
    assert out.shape == (3, 3)
    assert out[:, 0].tolist() == [2.0, 0.0, 1.0] and out[:, 1].tolist() == [0.0, 0.0, 0.0]
    assert v[:, 0].tolist() == [0.0, 0.0, 0.0]  # input untouched
    out = RT.assign_swizzle(v, "g", F(4.0))
    assert out[:, 0].tolist() == [0.0, 4.0, 0.0]
    assert RT.swizzle(RT.vec(4, 1.0, 2.0, 3.0, 4.0), "wzyx")[:, 0].tolist() == [4.0, 3.0, 2.0, 1.0]
    assert RT.swizzle(RT.vec(4, 1.0, 2.0, 3.0, 4.0), "b").tolist() == [3.0]
    assert RT.swizzle(F(2.0), "xxx").shape == (3, 1)


@pytest.mark.parametrize("size", [3, 8])
def test_dynamic_index_clamps_per_lane(size):
    arr = np.arange(size, dtype=np.float32).reshape(size, 1) * 10
    idx = np.array([-5, 0, 1, size - 1, size, 100], dtype=np.int32)
    got = RT.index(arr, idx)
    assert got.tolist() == [0, 0, 10, (size - 1) * 10, (size - 1) * 10, (size - 1) * 10]
    assert RT.index(arr, 1).tolist() == [10.0]
    vecs = np.stack([RT.vec(2, float(k), -float(k)) for k in range(size)])  # vec2[size]
    got = RT.index(vecs, idx)
    assert got.shape == (2, 6) and got[1].tolist() == [
        0,
        0,
        -1,
        -(size - 1),
        -(size - 1),
        -(size - 1),
    ]


def test_assign_index_per_lane_with_mask():
    arr = np.zeros((4, 1), dtype=np.float32)
    idx = np.array([0, 3, 9, -1], dtype=np.int32)
    mask = np.array([True, True, True, False])
    out = RT.assign_index(arr, idx, np.array([1, 2, 3, 4], dtype=np.float32), mask)
    assert out.shape == (4, 4)
    assert out[:, 0].tolist() == [1, 0, 0, 0]
    assert out[:, 1].tolist() == [0, 0, 0, 2]
    assert out[:, 2].tolist() == [0, 0, 0, 3]  # 9 clamps to 3
    assert out[:, 3].tolist() == [0, 0, 0, 0]  # masked off
    m = RT.mat(2, 2, F(1.0))
    m2 = RT.assign_index(m, 1, RT.vec(2, 7.0, 8.0))
    assert m2[1, :, 0].tolist() == [7.0, 8.0] and m[1, :, 0].tolist() == [0.0, 1.0]


# ---------------------------------------------------------------- built-ins: hand-computed values
CASES = [
    ("radians", (180.0,), math.pi),
    ("degrees", (math.pi,), 180.0),
    ("sin", (0.0,), 0.0),
    ("cos", (0.0,), 1.0),
    ("tan", (0.0,), 0.0),
    ("asin", (1.0,), math.pi / 2),
    ("asin", (0.0,), 0.0),
    ("asin", (2.0,), NAN),
    ("acos", (1.0,), 0.0),
    ("acos", (-1.0,), math.pi),
    ("atan", (1.0,), math.pi / 4),
    ("atan", (0.0, 0.0), 3 * math.pi / 4),
    ("atan", (-0.0, -1.0), -math.pi),
    ("atan", (1.0, 0.0), math.pi / 2),
    ("sinh", (0.0,), 0.0),
    ("cosh", (0.0,), 1.0),
    ("tanh", (100.0,), 1.0),
    ("asinh", (0.0,), 0.0),
    ("acosh", (1.0,), 0.0),
    ("acosh", (0.5,), NAN),
    ("atanh", (0.0,), 0.0),
    ("atanh", (1.0,), math.inf),
    ("pow", (2.0, 10.0), 1024.0),
    ("pow", (-2.0, 2.0), NAN),
    ("pow", (0.0, 0.0), 0.0),
    ("pow", (0.0, -1.0), 0.0),
    ("pow", (NAN, 0.0), 0.0),
    ("exp", (0.0,), 1.0),
    ("log", (1.0,), 0.0),
    ("log", (0.0,), -math.inf),
    ("exp2", (3.0,), 8.0),
    ("log2", (8.0,), 3.0),
    ("sqrt", (4.0,), 2.0),
    ("sqrt", (-1.0,), NAN),
    ("inversesqrt", (4.0,), 0.5),
    ("inversesqrt", (0.0,), math.inf),
    ("abs", (-2.0,), 2.0),
    ("sign", (-2.0,), -1.0),
    ("sign", (NAN,), 0.0),
    ("floor", (-0.5,), -1.0),
    ("ceil", (-0.5,), -0.0),
    ("trunc", (-1.5,), -1.0),
    ("round", (2.5,), 2.0),
    ("round", (-2.5,), -2.0),
    ("round", (3.5,), 4.0),
    ("roundEven", (2.5,), 2.0),
    ("fract", (-0.25,), 0.75),
    ("fract", (-1e-9,), 1.0),
    ("mod", (-7.5, 2.0), 0.5),
    ("mod", (7.5, -2.0), -0.5),
    ("mod", (1.0, 0.0), NAN),
    ("min_", (NAN, 1.0), 1.0),
    ("max_", (1.0, NAN), 1.0),
    ("clamp", (0.5, 1.0, 0.0), 0.0),
    ("clamp", (NAN, 0.0, 1.0), 0.0),
    ("mix", (1.0, 3.0, 0.5), 2.0),
    ("step", (1.0, 0.5), 0.0),
    ("step", (1.0, 1.0), 1.0),
    ("smoothstep", (0.0, 1.0, 0.5), 0.5),
    ("smoothstep", (1.0, 1.0, 0.5), 0.0),
    ("smoothstep", (1.0, 1.0, 2.0), 1.0),
    ("smoothstep", (2.0, 1.0, 1.5), 0.5),
    ("normalize", (0.0,), 0.0),
    ("normalize", (-3.0,), -1.0),
    ("length", (-3.0,), 3.0),
]


@pytest.mark.parametrize("name,args,expected", CASES, ids=[f"{c[0]}{c[1]}" for c in CASES])
def test_builtin_values(name, args, expected):
    got = getattr(RT, name)(*(F(a) for a in args))
    assert got.dtype == np.float32
    g = float(val(got))
    if math.isnan(expected):
        assert math.isnan(g)
    else:
        # atan/asin/acos are Mesa's polynomial approximations (abs. error < 1e-5 rad, within
        # GLSL's allowance); everything else here is exact or correctly rounded float32.
        tol = 1e-5 if name in ("atan", "asin", "acos") else 1e-7
        assert g == pytest.approx(expected, rel=2e-6, abs=tol)
        if expected == 0.0:
            assert math.copysign(1, g) == math.copysign(1, expected), "sign of zero"


def test_modf_and_mix_bool():
    fr, ip = RT.modf(F(-2.5))
    assert val(fr) == -0.5 and val(ip) == -2.0
    assert RT.mix(F(1.0), F(2.0), B(True)).tolist() == [2.0]
    sel = RT.mix(RT.vec(2, 1.0, 1.0), RT.vec(2, 2.0, 2.0), RT.bvec(2, B(False), B(True)))
    assert sel[:, 0].tolist() == [1.0, 2.0]


def test_geometric():
    v = RT.vec(3, 3.0, 4.0, 0.0)
    assert val(RT.length(v)) == 5.0
    assert val(RT.distance(v, RT.vec(3, 0.0))) == 5.0
    assert val(RT.dot(v, v)) == 25.0
    assert RT.cross(RT.vec(3, 1.0, 0.0, 0.0), RT.vec(3, 0.0, 1.0, 0.0))[:, 0].tolist() == [0, 0, 1]
    n = RT.normalize(v)
    assert n[:, 0].tolist() == pytest.approx([0.6, 0.8, 0.0])
    assert np.isnan(RT.normalize(RT.vec(3, 0.0))).all()
    i = RT.vec(2, 1.0, -1.0)
    nn = RT.vec(2, 0.0, 1.0)
    assert RT.reflect(i, nn)[:, 0].tolist() == [1.0, 1.0]
    assert RT.faceforward(nn, i, nn)[:, 0].tolist() == [0.0, 1.0]
    assert RT.faceforward(nn, RT.neg(i), nn)[:, 0].tolist() == [0.0, -1.0]
    r = RT.refract(RT.vec(2, 0.8, -0.6), nn, F(1.5))  # total internal reflection: k < 0
    assert r[:, 0].tolist() == [0.0, 0.0]
    r = RT.refract(RT.vec(2, 0.0, -1.0), nn, F(0.5))
    assert r[:, 0].tolist() == pytest.approx([0.0, -1.0])


def test_bit_casts_and_packing():
    assert RT.floatBitsToInt(F(1.0)).tolist() == [0x3F800000]
    assert RT.floatBitsToUint(F(-0.0)).tolist() == [0x80000000]
    assert RT.intBitsToFloat(I(0x3F800000)).tolist() == [1.0]
    assert RT.uintBitsToFloat(U(0xBF800000)).tolist() == [-1.0]
    assert RT.isnan(RT.intBitsToFloat(I(0x7FC00001))).tolist() == [True]
    assert RT.isinf(F(math.inf)).tolist() == [True]
    p = RT.packSnorm2x16(RT.vec(2, 0.5, -1.0))
    assert p.dtype == np.uint32 and p.tolist() == [0x80014000]
    assert RT.unpackSnorm2x16(p)[:, 0].tolist() == pytest.approx([16384 / 32767, -1.0])
    assert RT.unpackSnorm2x16(U(0x8000))[0].tolist() == [-1.0]
    p = RT.packUnorm2x16(RT.vec(2, 0.5, 2.0))
    assert p.tolist() == [0xFFFF8000]
    assert RT.unpackUnorm2x16(p)[:, 0].tolist() == pytest.approx([32768 / 65535, 1.0])
    assert RT.packUnorm2x16(RT.vec(2, NAN, 0.0)).tolist() == [0]
    p = RT.packHalf2x16(RT.vec(2, 1.0, -2.0))
    assert p.tolist() == [0xC0003C00]
    assert RT.unpackHalf2x16(p)[:, 0].tolist() == [1.0, -2.0]
    assert RT.packHalf2x16(RT.vec(2, 65520.0, 0.0)).tolist() == [0x7C00]


def test_derivatives_fine_quads():
    w, h = 4, 2
    x = np.tile(np.arange(w, dtype=np.float32), h)
    y = np.repeat(np.arange(h, dtype=np.float32), w)
    v = x * x + 10 * y * x
    dx = RT.dFdx(v, w).reshape(h, w)
    # row 0: x*x -> pairs (0,1), (2,3): 1, 5; row 1: x*x + 10x -> 11, 15
    assert dx.tolist() == [[1, 1, 5, 5], [11, 11, 15, 15]]
    dy = RT.dFdy(v, w).reshape(h, w)
    assert dy.tolist() == [[0, 10, 20, 30]] * 2
    assert RT.fwidth(v, w).reshape(h, w)[1].tolist() == [11, 21, 35, 45]
    assert RT.dFdx(F(3.0), w).tolist() == [0.0]
    vec = np.stack([v, 2 * v])
    assert RT.dFdx(vec, w).shape == (2, w * h)
    odd = RT.dFdx(np.arange(3, dtype=np.float32), 3)
    assert odd.tolist() == [1, 1, 1]


def test_texture_unsupported_raises():
    with pytest.raises(GLSLRuntimeError, match="texture.*line 12"):
        RT.texture_unsupported("texture", 12)


# ---------------------------------------------------------------- precision modes keep dtype
ALL_FLOAT_FUNCS_1 = [
    "radians",
    "degrees",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
    "exp",
    "log",
    "exp2",
    "log2",
    "sqrt",
    "inversesqrt",
    "abs",
    "sign",
    "floor",
    "ceil",
    "trunc",
    "round",
    "roundEven",
    "fract",
    "length",
    "normalize",
    "neg",
]
ALL_FLOAT_FUNCS_2 = [
    "add",
    "sub",
    "mul",
    "div",
    "pow",
    "mod",
    "min_",
    "max_",
    "step",
    "atan",
    "distance",
    "dot",
    "matrixCompMult",
]


@pytest.mark.parametrize(
    "precision,dtype", [("float16", np.float16), ("float32", np.float32), ("float64", np.float64)]
)
def test_precision_modes_keep_dtype(precision, dtype):
    rt = Runtime(precision)
    with rt.errstate():
        x = np.linspace(-2, 2, 7).astype(dtype)
        y = np.linspace(0.5, 3, 7).astype(dtype)
        for name in ALL_FLOAT_FUNCS_1:
            assert getattr(rt, name)(x).dtype == dtype, name
        for name in ALL_FLOAT_FUNCS_2:
            assert getattr(rt, name)(x, y).dtype == dtype, name
        assert rt.add(x, 1.5).dtype == dtype  # Python floats never promote
        assert rt.add(x, np.float64(1.5)).dtype == dtype or precision == "float64"
        for name in ("clamp", "mix", "smoothstep"):
            assert getattr(rt, name)(x, y, rt.f(0.5)).dtype == dtype, name
        v = rt.vec(3, x, y, 1.0)
        assert v.dtype == dtype
        assert rt.cross(v, v).dtype == dtype
        assert rt.reflect(v, v).dtype == dtype and rt.refract(v, v, rt.f(0.5)).dtype == dtype
        assert rt.faceforward(v, v, v).dtype == dtype
        m = rt.mat(3, 3, rt.f(2.0))
        for out in (
            rt.mat_mul_vec(m, v),
            rt.vec_mul_mat(v, m),
            rt.mat_mul_mat(m, m),
            rt.inverse(m),
            rt.determinant(m),
            rt.transpose(m),
            rt.outerProduct(v, v),
        ):
            assert out.dtype == dtype
        assert rt.modf(x)[0].dtype == dtype and rt.modf(x)[1].dtype == dtype
        assert rt.to_float(I(3)).dtype == dtype
        assert rt.intBitsToFloat(I(0x3F800000)).dtype == dtype
        assert rt.unpackHalf2x16(U(0x3C00)).dtype == dtype
        assert rt.dFdx(np.tile(x[:4], 2), 4).dtype == dtype


def test_float16_rounds_each_operation():
    rt = Runtime("float16")
    a = rt.f(2049.0)  # not representable in float16: rounds to 2048
    assert a.tolist() == [2048.0]
    assert rt.add(rt.f(2048.0), rt.f(1.0)).tolist() == [2048.0]  # 2049 rounds to even


def test_runtime_rejects_unknown_precision():
    with pytest.raises(ValueError):
        Runtime("float8")
