"""The GLSL ES 3.00 type objects and the typing rules in glslcheck.language.glsl_types (spec 4.1,
5.4-5.9)."""

import pytest

from glslcheck.language import glsl_types as T
from glslcheck.language.glsl_types import (
    BY_NAME,
    ArrayType,
    StructType,
    assign_result,
    binary_result,
    conditional_result,
    constructor_check,
    constructor_result,
    index_result,
    matrix,
    swizzle_is_lvalue,
    swizzle_result,
    unary_result,
    vector,
)

t = BY_NAME.__getitem__  # t("vec3")


# --- type objects --------------------------------------------------------------------


def test_every_builtin_type_name_round_trips():
    for name, ty in BY_NAME.items():
        if name in ("mat2x2", "mat3x3", "mat4x4"):
            assert str(ty) == name[:4]
        else:
            assert str(ty) == name
    assert len(BY_NAME) == 1 + 4 + 12 + 12 + 15  # void, scalars, vectors, matrices, samplers


def test_interning_and_aliases():
    assert t("mat2") is t("mat2x2") is matrix(2, 2)
    assert vector("float", 3) is t("vec3")
    assert vector("int", 1) is T.INT
    assert hash(t("vec3")) == hash(vector("float", 3))
    assert {t("vec3"), vector("float", 3)} == {t("vec3")}


@pytest.mark.parametrize(
    "name, base, size, cols, rows, kind",
    [
        ("float", "float", 1, 1, 1, "scalar"),
        ("uint", "uint", 1, 1, 1, "scalar"),
        ("bvec2", "bool", 2, 1, 2, "vector"),
        ("ivec4", "int", 4, 1, 4, "vector"),
        ("mat2x3", "float", 6, 2, 3, "matrix"),
        ("mat4x2", "float", 8, 4, 2, "matrix"),
        ("mat3", "float", 9, 3, 3, "matrix"),
    ],
)
def test_basic_type_properties(name, base, size, cols, rows, kind):
    ty = t(name)
    assert (ty.base, ty.size, ty.cols, ty.rows) == (base, size, cols, rows)
    assert (ty.is_scalar, ty.is_vector, ty.is_matrix) == (
        kind == "scalar",
        kind == "vector",
        kind == "matrix",
    )
    assert ty.is_numeric == (base != "bool")
    assert not ty.is_opaque
    assert ty.component_type is T.SCALARS[base]


def test_matrix_column_type_and_indexing():
    assert t("mat2x3").column_type is t("vec3")
    assert index_result(t("mat2x3")) is t("vec3")
    assert index_result(t("ivec3")) is T.INT
    assert index_result(ArrayType(t("vec2"), 3)) is t("vec2")
    assert isinstance(index_result(T.FLOAT), str)


def test_samplers():
    s = t("isampler2DArray")
    assert s.is_opaque and s.contains_opaque and not s.is_numeric and s.base is None
    assert (s.result, s.dim, s.shadow, s.coord_size) == ("int", "2DArray", False, 3)
    cube = t("samplerCubeShadow")
    assert (cube.result, cube.dim, cube.shadow, cube.coord_size) == ("float", "Cube", True, 4)
    assert t("usampler3D").result == "uint"


def test_void():
    assert str(T.VOID) == "void" and T.VOID.is_void and T.VOID.base is None


def test_arrays():
    a = ArrayType(T.FLOAT, 3)
    assert str(a) == "float[3]" and str(ArrayType(t("vec2"))) == "vec2[]"
    assert a == ArrayType(T.FLOAT, 3) and hash(a) == hash(ArrayType(T.FLOAT, 3))
    assert a != ArrayType(T.FLOAT, 4) and a.is_array and not a.is_numeric
    assert ArrayType(t("sampler2D"), 2).contains_opaque


def test_structs_are_nominal():
    s1 = StructType("S", (("a", T.FLOAT), ("b", t("vec3"))))
    s2 = StructType("S", (("a", T.FLOAT), ("b", t("vec3"))))
    assert s1 == s1 and s1 != s2
    assert len({s1, s2}) == 2
    assert str(s1) == "S" and s1.field_type("b") is t("vec3") and s1.field_type("c") is None
    assert StructType("U", (("s", t("sampler2D")),)).contains_opaque


def test_types_are_immutable():
    with pytest.raises(AttributeError):
        t("vec3").n = 4


# --- binary operators ------------------------------------------------------------------

OK = [
    # op, left, right, result
    ("+", "float", "float", "float"),
    ("-", "int", "int", "int"),
    ("*", "uint", "uint", "uint"),
    ("/", "vec3", "vec3", "vec3"),
    ("+", "float", "vec3", "vec3"),
    ("*", "vec3", "float", "vec3"),
    ("-", "ivec2", "int", "ivec2"),
    ("/", "uint", "uvec4", "uvec4"),
    ("+", "mat3", "mat3", "mat3"),
    ("-", "mat2x3", "mat2x3", "mat2x3"),
    ("/", "mat4", "mat4", "mat4"),
    ("*", "float", "mat2", "mat2"),
    ("/", "mat3x2", "float", "mat3x2"),
    ("+", "mat2", "float", "mat2"),
    ("*", "mat3", "vec3", "vec3"),
    ("*", "vec3", "mat3", "vec3"),
    ("*", "mat2x3", "vec2", "vec3"),
    ("*", "vec3", "mat2x3", "vec2"),
    ("*", "mat2x3", "mat4x2", "mat4x3"),
    ("*", "mat3x2", "mat2x3", "mat2"),
    ("*", "mat2x3", "mat3x2", "mat3"),
    ("*", "mat4", "mat4", "mat4"),
    ("%", "int", "int", "int"),
    ("%", "uvec3", "uint", "uvec3"),
    ("%", "int", "ivec2", "ivec2"),
    ("<", "float", "float", "bool"),
    (">=", "int", "int", "bool"),
    ("<=", "uint", "uint", "bool"),
    ("==", "vec3", "vec3", "bool"),
    ("!=", "mat2", "mat2", "bool"),
    ("==", "bvec2", "bvec2", "bool"),
    ("&&", "bool", "bool", "bool"),
    ("^^", "bool", "bool", "bool"),
    ("||", "bool", "bool", "bool"),
    ("&", "int", "int", "int"),
    ("|", "uvec2", "uvec2", "uvec2"),
    ("^", "ivec3", "int", "ivec3"),
    ("&", "uint", "uvec4", "uvec4"),
    ("<<", "int", "uint", "int"),
    (">>", "uvec2", "ivec2", "uvec2"),
    ("<<", "ivec3", "int", "ivec3"),
    (">>", "uint", "int", "uint"),
]


@pytest.mark.parametrize("op, left, right, result", OK)
def test_binary_ok(op, left, right, result):
    assert binary_result(op, t(left), t(right)) is t(result)


BAD = [
    ("+", "int", "float", "no implicit conversion"),
    ("*", "vec3", "ivec3", "no implicit"),
    ("+", "vec3", "vec2", "vector sizes differ"),
    ("-", "uint", "int", "no implicit"),
    ("+", "bool", "bool", "not numeric"),
    ("*", "bvec2", "bvec2", "not numeric"),
    ("*", "mat3", "vec2", "3 columns"),
    ("*", "vec2", "mat3", "3 rows"),
    ("*", "mat2x3", "mat2x3", "columns"),
    ("+", "mat2", "mat3", "same type"),
    ("+", "mat3", "vec3", "same type"),
    ("/", "vec3", "mat3", "same type"),
    ("*", "mat2", "int", "no implicit"),
    ("*", "mat2", "ivec2", "no implicit"),
    ("%", "float", "float", "int or uint"),
    ("%", "ivec2", "ivec3", "sizes differ"),
    ("%", "int", "uint", "no implicit"),
    ("<", "vec2", "vec2", "lessThan()"),
    (">", "int", "float", "no implicit"),
    ("<", "bool", "bool", "numeric scalars"),
    ("==", "vec3", "vec2", "same type"),
    ("==", "int", "float", "no implicit"),
    ("==", "sampler2D", "sampler2D", "samplers"),
    ("&&", "bvec2", "bvec2", "bool scalars"),
    ("||", "int", "int", "bool scalars"),
    ("&", "float", "float", "int or uint"),
    ("|", "int", "uint", "no implicit"),
    ("^", "ivec2", "ivec3", "sizes differ"),
    ("<<", "int", "ivec2", "scalar cannot be shifted by a vector"),
    (">>", "float", "int", "int or uint"),
    ("<<", "ivec2", "ivec3", "sizes differ"),
]


@pytest.mark.parametrize("op, left, right, fragment", BAD)
def test_binary_errors(op, left, right, fragment):
    msg = binary_result(op, t(left), t(right))
    assert isinstance(msg, str), msg
    assert fragment in msg
    assert f"'{left}'" in msg and f"'{right}'" in msg


def test_binary_error_wording():
    assert binary_result("+", t("vec3"), t("vec2")).startswith("cannot add 'vec3' and 'vec2'")
    assert binary_result("-", T.INT, T.FLOAT).startswith("cannot subtract 'float' from 'int'")
    assert binary_result("*", T.INT, T.FLOAT).startswith("cannot multiply 'int' by 'float'")
    assert binary_result("/", T.INT, T.FLOAT).startswith("cannot divide 'int' by 'float'")


def test_equality_of_arrays_and_structs():
    s = StructType("S", (("a", T.FLOAT),))
    assert binary_result("==", s, s) is T.BOOL
    assert isinstance(binary_result("==", s, StructType("S", (("a", T.FLOAT),))), str)
    assert binary_result("==", ArrayType(T.FLOAT, 2), ArrayType(T.FLOAT, 2)) is T.BOOL
    assert isinstance(binary_result("!=", ArrayType(T.FLOAT, 2), ArrayType(T.FLOAT, 3)), str)
    opaque = StructType("O", (("s", t("sampler2D")),))
    assert "samplers" in binary_result("==", opaque, opaque)


def test_unknown_operator_raises():
    with pytest.raises(ValueError):
        binary_result("**", T.FLOAT, T.FLOAT)
    with pytest.raises(ValueError):
        unary_result("*", T.FLOAT)


@pytest.mark.parametrize(
    "op, target, value, ok",
    [
        ("=", "vec3", "vec3", True),
        ("=", "vec3", "ivec3", False),
        ("=", "float", "int", False),
        ("+=", "vec3", "float", True),
        ("+=", "float", "vec3", False),
        ("*=", "vec3", "mat3", True),
        ("*=", "mat3", "vec3", False),
        ("*=", "mat3", "mat3", True),
        ("*=", "mat2x3", "mat2", True),
        ("*=", "mat2x3", "mat3x2", False),
        ("%=", "ivec2", "int", True),
        ("<<=", "int", "uint", True),
        ("&=", "uvec2", "uint", True),
        ("-=", "int", "float", False),
        ("=", "sampler2D", "sampler2D", False),
    ],
)
def test_assign(op, target, value, ok):
    r = assign_result(op, t(target), t(value))
    assert (r is t(target)) if ok else isinstance(r, str), r


def test_conditional():
    assert conditional_result(T.BOOL, t("vec3"), t("vec3")) is t("vec3")
    assert conditional_result(T.BOOL, ArrayType(T.FLOAT, 2), ArrayType(T.FLOAT, 2)) == ArrayType(
        T.FLOAT, 2
    )
    s = StructType("S", (("a", T.FLOAT),))
    assert conditional_result(T.BOOL, s, s) is s
    assert "mix()" in conditional_result(t("bvec2"), T.FLOAT, T.FLOAT)
    assert "must be a bool" in conditional_result(T.INT, T.FLOAT, T.FLOAT)
    assert "no implicit" in conditional_result(T.BOOL, T.FLOAT, T.INT)
    assert "different types" in conditional_result(T.BOOL, t("vec2"), t("vec3"))
    assert isinstance(conditional_result(T.BOOL, t("sampler2D"), t("sampler2D")), str)


# --- unary operators -----------------------------------------------------------------


@pytest.mark.parametrize(
    "op, operand, result",
    [
        ("-", "float", "float"),
        ("-", "mat3", "mat3"),
        ("+", "ivec2", "ivec2"),
        ("-", "uvec3", "uvec3"),
        ("!", "bool", "bool"),
        ("~", "int", "int"),
        ("~", "uvec4", "uvec4"),
        ("++", "float", "float"),
        ("--", "ivec3", "ivec3"),
        ("++", "mat2", "mat2"),
        ("-", "bool", None),
        ("!", "bvec2", None),
        ("!", "int", None),
        ("~", "float", None),
        ("~", "mat2", None),
        ("++", "bool", None),
        ("-", "sampler2D", None),
        ("+", "bvec3", None),
    ],
)
def test_unary(op, operand, result):
    r = unary_result(op, t(operand))
    if result is None:
        assert isinstance(r, str) and f"'{operand}'" in r
    else:
        assert r is t(result)


def test_unary_bvec_hint():
    assert "not()" in unary_result("!", t("bvec2"))


# --- swizzles --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "ty, fields, result",
    [
        ("vec4", "x", "float"),
        ("vec4", "xyz", "vec3"),
        ("vec2", "yx", "vec2"),
        ("vec3", "rgba"[:3], "vec3"),
        ("ivec4", "stpq", "ivec4"),
        ("bvec2", "xxxx", "bvec4"),
        ("uvec3", "bgr", "uvec3"),
        ("vec2", "ts", "vec2"),
    ],
)
def test_swizzle_ok(ty, fields, result):
    assert swizzle_result(t(ty), fields) is t(result)


@pytest.mark.parametrize(
    "ty, fields, fragment",
    [
        ("vec2", "z", "beyond"),
        ("vec3", "w", "beyond"),
        ("vec2", "xb", "mixes"),
        ("vec4", "xyzwx", "more than 4"),
        ("float", "x", "scalar"),
        ("mat2", "x", "no components"),
        ("vec4", "q2", "no field"),
        ("vec4", "", "no field"),
        ("vec4", "rgq", "mixes"),
    ],
)
def test_swizzle_errors(ty, fields, fragment):
    r = swizzle_result(t(ty), fields)
    assert isinstance(r, str) and fragment in r, r


def test_swizzle_lvalue():
    assert swizzle_is_lvalue("xy") and swizzle_is_lvalue("wzyx") and swizzle_is_lvalue("r")
    assert not swizzle_is_lvalue("xx") and not swizzle_is_lvalue("xyx")


# --- constructors ----------------------------------------------------------------------


def _args(spec):
    return [t(a) for a in spec.split()]


@pytest.mark.parametrize(
    "target, args",
    [
        ("float", "int"),
        ("int", "float"),
        ("uint", "bool"),
        ("bool", "uint"),
        ("float", "vec3"),
        ("int", "mat2"),
        ("float", "float"),
        ("vec3", "float"),
        ("vec3", "int"),
        ("vec4", "vec2 vec2"),
        ("vec4", "vec3 float"),
        ("vec2", "vec4"),
        ("ivec3", "vec3"),
        ("bvec2", "float int"),
        ("vec3", "vec2 vec2"),
        ("vec4", "mat2"),
        ("vec4", "mat3"),
        ("vec4", "vec3 mat2"),
        ("bvec2", "mat2"),
        ("vec4", "float float float float"),
        ("mat2", "float"),
        ("mat3", "int"),
        ("mat2", "bool"),
        ("mat3", "mat4"),
        ("mat4", "mat2"),
        ("mat2x3", "mat4x2"),
        ("mat2", "vec4"),
        ("mat2", "ivec4"),
        ("mat2", "vec2 vec2"),
        ("mat2", "vec3 float"),
        ("mat2", "vec3 vec2"),
        ("mat2x3", "vec3 vec3"),
        ("mat3", "float float float float float float float float vec2"),
    ],
)
def test_constructor_ok(target, args):
    assert constructor_check(t(target), _args(args)) is None


@pytest.mark.parametrize(
    "target, args, fragment",
    [
        ("float", "", "needs arguments"),
        ("vec3", "", "needs arguments"),
        ("float", "vec3 float", "too many"),
        ("float", "mat2 float", "too many"),
        ("vec3", "vec2", "not enough"),
        ("vec4", "vec2 float", "not enough"),
        ("vec2", "vec2 float", "too many"),
        ("vec3", "vec3 vec3", "too many"),
        ("vec2", "float float float", "too many"),
        ("mat2", "vec4 float", "too many"),
        ("mat2", "mat2 float", "only argument"),
        ("mat2", "vec2 vec2 float", "too many"),
        ("mat3", "vec3 vec3", "not enough"),
        ("mat2", "vec3", "not enough"),
        ("mat2", "mat2 mat2", "only argument"),
        ("sampler2D", "int", "cannot be constructed"),
        ("void", "float", "cannot be constructed"),
        ("vec3", "sampler2D", "cannot be constructed from"),
    ],
)
def test_constructor_errors(target, args, fragment):
    r = constructor_check(t(target), _args(args))
    assert isinstance(r, str) and fragment in r, r


def test_struct_constructor():
    s = StructType("S", (("a", T.FLOAT), ("b", t("vec3"))))
    assert constructor_check(s, [T.FLOAT, t("vec3")]) is None
    assert "too" not in (constructor_check(s, [T.FLOAT]) or "")
    assert "2 arguments" in constructor_check(s, [T.FLOAT])
    assert "field 'b'" in constructor_check(s, [T.FLOAT, t("vec2")])
    assert "field 'a'" in constructor_check(s, [T.INT, t("vec3")])  # no conversion in structs
    inner = StructType("I", (("x", T.INT),))
    outer = StructType("O", (("i", inner), ("f", ArrayType(T.FLOAT, 2))))
    assert constructor_check(outer, [inner, ArrayType(T.FLOAT, 2)]) is None
    assert constructor_check(StructType("U", (("s", t("sampler2D")),)), [t("sampler2D")])


def test_array_constructor():
    assert constructor_check(ArrayType(T.FLOAT, 3), [T.FLOAT] * 3) is None
    assert "3 arguments" in constructor_check(ArrayType(T.FLOAT, 3), [T.FLOAT] * 2)
    assert "element 1" in constructor_check(ArrayType(T.FLOAT, 2), [T.FLOAT, T.INT])
    assert constructor_result(ArrayType(t("vec2")), [t("vec2")] * 4) == ArrayType(t("vec2"), 4)
    assert constructor_result(ArrayType(T.FLOAT, 2), [T.FLOAT] * 2) == ArrayType(T.FLOAT, 2)
    assert isinstance(constructor_result(ArrayType(T.FLOAT), []), str)
