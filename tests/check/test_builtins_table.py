"""The built-in function table, overload resolution and the predefined names
(glslcheck.language.builtin_functions)."""

import pytest

from glslcheck.language import builtin_functions as B
from glslcheck.language import glsl_types as T
from glslcheck.language.builtin_functions import BUILTINS, resolve
from glslcheck.language.glsl_types import BY_NAME, ArrayType

t = BY_NAME.__getitem__

# Every function of GLSL ES 3.00 chapter 8, and nothing from later versions.
SPEC_NAMES = """
radians degrees sin cos tan asin acos atan sinh cosh tanh asinh acosh atanh
pow exp log exp2 log2 sqrt inversesqrt
abs sign floor trunc round roundEven ceil fract mod modf min max clamp mix step smoothstep
isnan isinf floatBitsToInt floatBitsToUint intBitsToFloat uintBitsToFloat
packSnorm2x16 unpackSnorm2x16 packUnorm2x16 unpackUnorm2x16 packHalf2x16 unpackHalf2x16
length distance dot cross normalize faceforward reflect refract
matrixCompMult outerProduct transpose determinant inverse
lessThan lessThanEqual greaterThan greaterThanEqual equal notEqual any all not
textureSize texture textureProj textureLod textureOffset texelFetch texelFetchOffset
textureProjOffset textureLodOffset textureProjLod textureProjLodOffset textureGrad
textureGradOffset textureProjGrad textureProjGradOffset dFdx dFdy fwidth
""".split()


def test_table_has_exactly_the_spec_functions():
    assert set(BUILTINS) == set(SPEC_NAMES)
    for later in (
        "fma",
        "frexp",
        "ldexp",
        "bitfieldExtract",
        "packUnorm4x8",
        "textureGather",
        "texture2D",
        "imageLoad",
    ):
        assert later not in BUILTINS


def test_every_overload_is_well_formed():
    for name, fn in BUILTINS.items():
        assert fn.name == name and fn.overloads
        assert fn.category in B.CATEGORIES and fn.cost in B.COST_ORDER
        seen = set()
        for ov in fn.overloads:
            assert ov.name == name and ov.category == fn.category and ov.cost == fn.cost
            assert len(ov.params) == len(ov.qualifiers)
            assert set(ov.qualifiers) <= {"in", "out"}
            assert ov.params not in seen, f"duplicate overload {ov}"
            seen.add(ov.params)
            assert not ov.returns.is_void


@pytest.mark.parametrize("name", SPEC_NAMES)
def test_each_builtin_resolves_each_of_its_overloads(name):
    for ov in BUILTINS[name].overloads:
        assert resolve(name, list(ov.params)) is ov


@pytest.mark.parametrize(
    "call, result",
    [
        ("sin float", "float"),
        ("atan vec2 vec2", "vec2"),
        ("atan vec3", "vec3"),
        ("pow vec4 vec4", "vec4"),
        ("abs int", "int"),
        ("abs ivec3", "ivec3"),
        ("sign ivec2", "ivec2"),
        ("mod vec3 float", "vec3"),
        ("mod vec3 vec3", "vec3"),
        ("modf vec2 vec2", "vec2"),
        ("min vec3 float", "vec3"),
        ("max uvec2 uint", "uvec2"),
        ("clamp ivec4 int int", "ivec4"),
        ("clamp vec2 vec2 vec2", "vec2"),
        ("clamp float float float", "float"),
        ("mix vec3 vec3 float", "vec3"),
        ("mix vec3 vec3 bvec3", "vec3"),
        ("mix float float bool", "float"),
        ("step float vec4", "vec4"),
        ("smoothstep float float vec2", "vec2"),
        ("isnan vec3", "bvec3"),
        ("floatBitsToInt vec2", "ivec2"),
        ("uintBitsToFloat uint", "float"),
        ("packHalf2x16 vec2", "uint"),
        ("unpackSnorm2x16 uint", "vec2"),
        ("length vec3", "float"),
        ("distance vec2 vec2", "float"),
        ("dot vec4 vec4", "float"),
        ("cross vec3 vec3", "vec3"),
        ("refract vec3 vec3 float", "vec3"),
        ("matrixCompMult mat2x3 mat2x3", "mat2x3"),
        ("outerProduct vec3 vec2", "mat2x3"),
        ("outerProduct vec2 vec4", "mat4x2"),
        ("transpose mat2x4", "mat4x2"),
        ("determinant mat3", "float"),
        ("inverse mat4", "mat4"),
        ("lessThan uvec3 uvec3", "bvec3"),
        ("equal bvec2 bvec2", "bvec2"),
        ("any bvec4", "bool"),
        ("not bvec2", "bvec2"),
        ("textureSize sampler2D int", "ivec2"),
        ("textureSize isampler3D int", "ivec3"),
        ("textureSize sampler2DArrayShadow int", "ivec3"),
        ("texture sampler2D vec2", "vec4"),
        ("texture usampler2D vec2 float", "uvec4"),
        ("texture samplerCubeShadow vec4", "float"),
        ("texture isampler2DArray vec3", "ivec4"),
        ("textureProj sampler2D vec3", "vec4"),
        ("textureProj sampler3D vec4 float", "vec4"),
        ("textureLod samplerCube vec3 float", "vec4"),
        ("texelFetch sampler2D ivec2 int", "vec4"),
        ("texelFetchOffset usampler3D ivec3 int ivec3", "uvec4"),
        ("textureGrad sampler2DArrayShadow vec4 vec2 vec2", "float"),
        ("textureProjGradOffset sampler2DShadow vec4 vec2 vec2 ivec2", "float"),
        ("dFdx vec2", "vec2"),
        ("fwidth float", "float"),
    ],
)
def test_resolve_picks_the_right_overload(call, result):
    name, *args = call.split()
    ov = resolve(name, [t(a) for a in args])
    assert not isinstance(ov, str), ov
    assert ov.returns is t(result)


@pytest.mark.parametrize(
    "call",
    [
        "pow float int",
        "sin int",
        "abs uint",
        "sign uvec2",
        "mod int int",
        "mix vec3 vec3 vec2",
        "mix ivec2 ivec2 bvec2",
        "min float int",
        "clamp vec3 float vec3",
        "step vec2 float",
        "smoothstep vec2 vec2 float",
        "length int",
        "dot vec3 vec2",
        "cross vec2 vec2",
        "lessThan float float",
        "lessThan bvec2 bvec2",
        "any bool",
        "not bool",
        "determinant mat2x3",
        "inverse mat3x2",
        "matrixCompMult mat2 mat3",
        "texture sampler2D vec3",
        "texture sampler2DArrayShadow vec4 float",
        "textureLod samplerCubeShadow vec4 float",
        "textureOffset samplerCube vec3 ivec3",
        "texelFetch samplerCube ivec3 int",
        "texelFetch sampler2DShadow ivec2 int",
        "textureSize sampler2D",
        "atan",
        "modf float",
        "outerProduct vec2",
    ],
)
def test_resolve_rejects(call):
    name, *args = call.split()
    msg = resolve(name, [t(a) for a in args])
    assert isinstance(msg, str)
    assert msg.startswith(f"no matching overload for '{name}(")
    assert "candidates:" in msg


def test_resolve_message_lists_candidates():
    msg = resolve("pow", [T.FLOAT, T.INT])
    assert msg == (
        "no matching overload for 'pow(float, int)'; candidates: pow(float, float), "
        "pow(vec2, vec2), pow(vec3, vec3), pow(vec4, vec4)"
    )
    assert "modf(float, out float)" in resolve("modf", [T.FLOAT])
    long = resolve("texture", [t("sampler2D"), t("vec3")])
    assert "texture(sampler2D, vec2)" in long and "texture(sampler2D, vec2, float)" in long
    assert "more" in long
    assert resolve("frobnicate", [T.FLOAT]) == "'frobnicate' is not a built-in function"
    assert isinstance(resolve("sin", [ArrayType(T.FLOAT, 2)]), str)


def test_out_parameters_and_fragment_only():
    ov = resolve("modf", [t("vec3"), t("vec3")])
    assert ov.qualifiers == ("in", "out") and ov.out_params == (1,)
    assert str(ov) == "vec3 modf(vec3, out vec3)"
    assert all(o.fragment_only for o in BUILTINS["dFdx"].overloads)
    assert resolve("texture", [t("sampler2D"), t("vec2"), T.FLOAT]).fragment_only
    assert not resolve("texture", [t("sampler2D"), t("vec2")]).fragment_only
    assert not resolve("sin", [T.FLOAT]).fragment_only


def test_overload_counts():
    # genType families expand to float, vec2, vec3, vec4.
    assert len(BUILTINS["sin"].overloads) == 4
    assert len(BUILTINS["min"].overloads) == 21  # (4 + 3) x float/int/uint
    assert len(BUILTINS["mix"].overloads) == 11  # 4 + 3 + 4
    assert len(BUILTINS["matrixCompMult"].overloads) == 9
    assert len(BUILTINS["outerProduct"].overloads) == 9
    assert len(BUILTINS["texture"].overloads) == 29
    assert len(BUILTINS["lessThan"].overloads) == 9 and len(BUILTINS["equal"].overloads) == 12


def test_categories_and_costs():
    assert BUILTINS["sin"].category == B.ANGLE_TRIG and BUILTINS["texture"].category == B.TEXTURE
    assert BUILTINS["packHalf2x16"].category == B.PACKING
    assert BUILTINS["dFdy"].category == B.DERIVATIVE
    for cheap in ("abs", "min", "max", "step", "fract", "floor"):
        assert BUILTINS[cheap].cost == B.CHEAP
    for medium in ("dot", "mix", "clamp"):
        assert BUILTINS[medium].cost == B.MEDIUM
    for expensive in (
        "sqrt",
        "pow",
        "exp",
        "log",
        "sin",
        "cos",
        "inversesqrt",
        "normalize",
        "length",
        "distance",
        "texture",
    ):
        assert BUILTINS[expensive].cost == B.EXPENSIVE
    assert {fn.category for fn in BUILTINS.values()} == set(B.CATEGORIES)


def test_constant_offset_functions():
    assert "textureOffset" in B.CONSTANT_OFFSET_FUNCTIONS
    assert "texelFetchOffset" in B.CONSTANT_OFFSET_FUNCTIONS
    assert "texture" not in B.CONSTANT_OFFSET_FUNCTIONS


def test_builtin_variables():
    v = B.BUILTIN_VARIABLES
    assert v["gl_FragCoord"].type is t("vec4") and v["gl_FragCoord"].storage == "in"
    assert v["gl_FrontFacing"].type is T.BOOL
    assert v["gl_PointCoord"].type is t("vec2")
    assert v["gl_FragDepth"].type is T.FLOAT and v["gl_FragDepth"].storage == "out"
    assert v["gl_MaxDrawBuffers"].value == 4 and v["gl_MaxDrawBuffers"].storage == "const"
    assert v["gl_MinProgramTexelOffset"].value == -8
    assert v["gl_MaxProgramTexelOffset"].value == 7
    assert v["gl_MaxFragmentUniformVectors"].value == 224
    assert v["gl_DepthRange"].type.field_type("far") is T.FLOAT
    assert sum(1 for x in v.values() if x.storage == "const") == 11


def test_shadertoy_uniforms():
    u = B.SHADERTOY_UNIFORMS
    assert u["iResolution"].type is t("vec3") and u["iResolution"].array_size is None
    assert u["iFrame"].type is T.INT
    assert u["iChannelTime"][:2] == (T.FLOAT, 4)
    assert u["iChannelTime"].declared_type == ArrayType(T.FLOAT, 4)
    assert u["iChannelResolution"].declared_type == ArrayType(t("vec3"), 4)
    assert u["iMouse"].type is t("vec4") and u["iDate"].type is t("vec4")
    for i in range(4):
        assert u[f"iChannel{i}"].type is t("sampler2D")
    assert set(u) == {
        "iResolution",
        "iTime",
        "iTimeDelta",
        "iFrameRate",
        "iFrame",
        "iChannelTime",
        "iChannelResolution",
        "iMouse",
        "iDate",
        "iSampleRate",
        "iChannel0",
        "iChannel1",
        "iChannel2",
        "iChannel3",
    }
    assert B.COMMON_TAB_UNIFORMS == {"iDate", "iSampleRate"} and B.COMMON_TAB_UNIFORMS <= set(u)
    assert all(isinstance(x.comment, str) and x.comment for x in u.values())


def test_keywords_and_reserved_words():
    assert {"const", "uniform", "struct", "precision", "highp", "invariant", "true"} <= B.KEYWORDS
    assert set(BY_NAME) <= B.KEYWORDS  # every built-in type name is a keyword
    assert {
        "attribute",
        "varying",
        "double",
        "sizeof",
        "using",
        "image2D",
        "sampler1D",
        "samplerBuffer",
        "dvec3",
        "goto",
        "union",
    } <= B.RESERVED_WORDS
    assert not B.KEYWORDS & B.RESERVED_WORDS
    assert "buffer" not in B.RESERVED_WORDS and "shared" not in B.RESERVED_WORDS  # ES 3.10
    assert not (B.KEYWORDS | B.RESERVED_WORDS) & set(BUILTINS)
