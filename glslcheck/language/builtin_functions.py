"""The tables of everything GLSL ES 3.00 and Shadertoy predefine.

This module owns, as data:

* :data:`BUILTINS` - every built-in function of GLSL ES 3.00 (spec chapter 8) with all its
  overloads (return type, parameter types, ``in``/``out`` qualifiers), its category and a
  relative cost class, and :func:`resolve` - exact-match overload resolution;
* :data:`BUILTIN_VARIABLES` - the fragment-shader built-in variables and constants (spec 7);
* :data:`SHADERTOY_UNIFORMS` and :data:`COMMON_TAB_UNIFORMS` - what Shadertoy declares
  around a tab (see ``/work/shared/SHADERTOY.md``);
* :data:`KEYWORDS` and :data:`RESERVED_WORDS` (spec 3.8).

The type checker, the linter and the NumPy transpiler all read these tables; nothing else
in the package lists built-ins. Signatures are written the way the spec writes them, with
its generic names (``genType``, ``genIType``, ``genUType``, ``genBType``, ``vec``,
``ivec``, ``uvec``, ``bvec``, ``mat``, ``gvec4``, ``gsampler2D`` ...) and expanded here
into concrete overloads.
"""

from __future__ import annotations

from collections import namedtuple
from collections.abc import Callable, Iterator, Mapping

from glslcheck.base.records import record
from glslcheck.language import glsl_types as T
from glslcheck.language.glsl_types import BY_NAME, ArrayType, StructType, Type
from glslcheck.shadertoy.wrapper import COMMON_ONLY_UNIFORMS as _COMMON_ONLY
from glslcheck.shadertoy.wrapper import UNIFORMS as _SHADERTOY_TABLE

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

# Categories: the sections of spec chapter 8.
ANGLE_TRIG = "angle-trig"  # 8.1
EXPONENTIAL = "exponential"  # 8.2
COMMON = "common"  # 8.3
PACKING = "floating-point pack/unpack"  # 8.4
GEOMETRIC = "geometric"  # 8.5
MATRIX = "matrix"  # 8.6
VECTOR_RELATIONAL = "vector-relational"  # 8.7
TEXTURE = "texture"  # 8.8
DERIVATIVE = "fragment-derivative"  # 8.9
CATEGORIES = (
    ANGLE_TRIG,
    EXPONENTIAL,
    COMMON,
    PACKING,
    GEOMETRIC,
    MATRIX,
    VECTOR_RELATIONAL,
    TEXTURE,
    DERIVATIVE,
)

# Relative cost per component, for the linter ("a built-in costlier than an add") and the
# benchmarks. cheap: about an add or a compare; medium: a few multiply-adds or a divide;
# expensive: a transcendental, a square root or a memory access.
CHEAP = "cheap"
MEDIUM = "medium"
EXPENSIVE = "expensive"
COST_ORDER = {CHEAP: 0, MEDIUM: 1, EXPENSIVE: 2}


@record(frozen=True)
class Overload:
    """One concrete signature of a built-in function."""

    name: str
    returns: Type
    params: tuple[Type, ...]
    qualifiers: tuple[str, ...]  # "in" or "out", one per parameter
    category: str
    cost: str
    #: Only valid in fragment shaders (derivatives, texture lookups with a bias argument).
    fragment_only: bool = False

    @property
    def out_params(self) -> tuple[int, ...]:
        """Indices of the ``out`` parameters (the caller must pass l-values there)."""
        return tuple(i for i, q in enumerate(self.qualifiers) if q == "out")

    def signature(self) -> str:
        """``modf(float, out float)``; the return type is left out, as in an error message."""
        args = ", ".join(
            ("out " if q == "out" else "") + str(p) for p, q in zip(self.params, self.qualifiers)
        )
        return f"{self.name}({args})"

    def __str__(self) -> str:
        return f"{self.returns} {self.signature()}"


@record(frozen=True)
class Builtin:
    """A built-in function name with all its overloads."""

    name: str
    category: str
    cost: str
    overloads: tuple[Overload, ...]


# ---------------------------------------------------------------------------------------
# Generic-signature expansion.

# Generic names that vary with the component count n; all of them in one signature share n.
_GEN_N = {
    "genType": ("float", (1, 2, 3, 4)),
    "genIType": ("int", (1, 2, 3, 4)),
    "genUType": ("uint", (1, 2, 3, 4)),
    "genBType": ("bool", (1, 2, 3, 4)),
    "vec": ("float", (2, 3, 4)),
    "ivec": ("int", (2, 3, 4)),
    "uvec": ("uint", (2, 3, 4)),
    "bvec": ("bool", (2, 3, 4)),
}
_MATS = [T.matrix(c, r) for c in (2, 3, 4) for r in (2, 3, 4)]
_SQUARE_MATS = [T.MAT2, T.MAT3, T.MAT4]


def _concrete(word: str, n: int | None, g: str, mat: Type | None) -> Type:
    if word in _GEN_N:
        assert n is not None, "a signature with a generic word has a component count"
        base = _GEN_N[word][0]
        return T.vector(base, n)
    if word == "mat":
        assert mat is not None, "a signature with `mat` is expanded over the matrices"
        return mat
    if word.startswith("g"):  # gvec4, gsampler2D, ...: g is "", "i" or "u"
        word = g + word[1:]
    return BY_NAME[word]


def _expand(sig: str) -> list[tuple[Type, tuple[Type, ...], tuple[str, ...]]]:
    """``"genType pow(genType, genType)"`` -> its concrete (return, params, qualifiers)."""
    head, paren, params = sig.partition("(")
    ret, *name = head.split()
    if not paren or len(name) != 1 or not params.rstrip().endswith(")"):
        raise ValueError(f"bad signature {sig!r}")
    words, quals = [], []
    for p in filter(None, (p.strip() for p in params.rstrip()[:-1].split(","))):
        q, _, w = p.rpartition(" ")
        words.append(w)
        quals.append(q or "in")
    every = [ret, *words]
    ns = next((_GEN_N[w][1] for w in every if w in _GEN_N), (None,))
    gs = (
        ("", "i", "u")
        if any(w.startswith("g") and not w.startswith("gen") for w in every)
        else ("",)
    )
    mats = _SQUARE_MATS if "sqmat" in sig else _MATS if "mat" in every else [None]
    every = ["mat" if w == "sqmat" else w for w in every]
    out = []
    for n in ns:
        for g in gs:
            for mat in mats:
                typed = [_concrete(w, n, g, mat) for w in every]
                out.append((typed[0], tuple(typed[1:]), tuple(quals)))
    return out


class _Table(Mapping):
    """:data:`BUILTINS`: function name -> :class:`Builtin`, built from the definitions below,
    which keep the spec's generic signatures; a function's concrete overloads are expanded
    when it is first looked up. A lint or check run looks up a few dozen of the 90-odd
    functions: expanding all of their 900-odd overloads at import would cost every start-up
    far more than it serves. Iterating over the names or testing
    `name in BUILTINS` expands nothing."""

    def __init__(self) -> None:
        # name -> (category, cost, [(signature, fragment_only) ...] or a function making the
        # overloads' (return, params) rows)
        self._defs: dict[str, tuple[str, str, Any]] = {}
        self._built: dict[str, Builtin] = {}

    def __getitem__(self, name: str) -> Builtin:
        fn = self._built.get(name)
        if fn is None:
            category, cost, forms = self._defs[name]  # KeyError: not a built-in
            fn = self._built[name] = Builtin(
                name, category, cost, tuple(_overloads(name, category, cost, forms))
            )
        return fn

    def __contains__(self, name: object) -> bool:
        return name in self._defs

    def __iter__(self) -> Iterator[str]:
        return iter(self._defs)

    def __len__(self) -> int:
        return len(self._defs)


def _overloads(name: str, category: str, cost: str, forms) -> list[Overload]:
    if callable(forms):  # _define_explicit's rows
        return [
            Overload(name, ret, params, ("in",) * len(params), category, cost)
            for ret, params in forms()
        ]
    overloads: list[Overload] = []
    for text, frag in forms:
        for ret, params, quals in _expand(text):
            if any(ov.params == params for ov in overloads):
                continue  # min(genType, float) at n=1 repeats min(genType, genType)
            overloads.append(Overload(name, ret, params, quals, category, cost, frag))
    return overloads


_TABLE = _Table()
BUILTINS: Mapping[str, Builtin] = _TABLE


def _define(name: str, category: str, cost: str, *sigs: str, fragment_only: bool = False) -> None:
    """Add overloads of ``name``; signatures ending in ``[, float bias]`` come in both forms."""
    forms = _TABLE._defs.setdefault(name, (category, cost, []))[2]
    for sig in sigs:
        if "[, float bias]" in sig:
            forms.append((sig.replace("[, float bias]", ""), fragment_only))
            forms.append((sig.replace("[, float bias]", ", float"), True))
        else:
            forms.append((sig, fragment_only))


def _define_explicit(
    name: str, category: str, cost: str, rows: Callable[[], list[tuple[Type, tuple[Type, ...]]]]
) -> None:
    """Add overloads that the generic names cannot express (transpose, outerProduct): `rows()`
    gives their (return, params)."""
    _TABLE._defs[name] = (category, cost, rows)


# 8.1 Angle and trigonometry functions.
for _n, _cost in [("radians", CHEAP), ("degrees", CHEAP)] + [
    (f, EXPENSIVE)
    for f in (
        "sin",
        "cos",
        "tan",
        "asin",
        "acos",
        "sinh",
        "cosh",
        "tanh",
        "asinh",
        "acosh",
        "atanh",
    )
]:
    _define(_n, ANGLE_TRIG, _cost, f"genType {_n}(genType)")
_define("atan", ANGLE_TRIG, EXPENSIVE, "genType atan(genType, genType)", "genType atan(genType)")

# 8.2 Exponential functions.
_define("pow", EXPONENTIAL, EXPENSIVE, "genType pow(genType, genType)")
for _n in ("exp", "log", "exp2", "log2", "sqrt", "inversesqrt"):
    _define(_n, EXPONENTIAL, EXPENSIVE, f"genType {_n}(genType)")

# 8.3 Common functions.
_define("abs", COMMON, CHEAP, "genType abs(genType)", "genIType abs(genIType)")
_define("sign", COMMON, CHEAP, "genType sign(genType)", "genIType sign(genIType)")
for _n in ("floor", "trunc", "round", "roundEven", "ceil", "fract"):
    _define(_n, COMMON, CHEAP, f"genType {_n}(genType)")
_define("mod", COMMON, MEDIUM, "genType mod(genType, float)", "genType mod(genType, genType)")
_define("modf", COMMON, CHEAP, "genType modf(genType, out genType)")
for _n in ("min", "max"):
    _define(
        _n,
        COMMON,
        CHEAP,
        f"genType {_n}(genType, genType)",
        f"genType {_n}(genType, float)",
        f"genIType {_n}(genIType, genIType)",
        f"genIType {_n}(genIType, int)",
        f"genUType {_n}(genUType, genUType)",
        f"genUType {_n}(genUType, uint)",
    )
_define(
    "clamp",
    COMMON,
    MEDIUM,
    "genType clamp(genType, genType, genType)",
    "genType clamp(genType, float, float)",
    "genIType clamp(genIType, genIType, genIType)",
    "genIType clamp(genIType, int, int)",
    "genUType clamp(genUType, genUType, genUType)",
    "genUType clamp(genUType, uint, uint)",
)
_define(
    "mix",
    COMMON,
    MEDIUM,
    "genType mix(genType, genType, genType)",
    "genType mix(genType, genType, float)",
    "genType mix(genType, genType, genBType)",
)
_define("step", COMMON, CHEAP, "genType step(genType, genType)", "genType step(float, genType)")
_define(
    "smoothstep",
    COMMON,
    MEDIUM,
    "genType smoothstep(genType, genType, genType)",
    "genType smoothstep(float, float, genType)",
)
_define("isnan", COMMON, CHEAP, "genBType isnan(genType)")
_define("isinf", COMMON, CHEAP, "genBType isinf(genType)")
_define("floatBitsToInt", COMMON, CHEAP, "genIType floatBitsToInt(genType)")
_define("floatBitsToUint", COMMON, CHEAP, "genUType floatBitsToUint(genType)")
_define("intBitsToFloat", COMMON, CHEAP, "genType intBitsToFloat(genIType)")
_define("uintBitsToFloat", COMMON, CHEAP, "genType uintBitsToFloat(genUType)")

# 8.4 Floating-point pack and unpack functions.
for _kind in ("Snorm", "Unorm", "Half"):
    _define(f"pack{_kind}2x16", PACKING, MEDIUM, f"uint pack{_kind}2x16(vec2)")
    _define(f"unpack{_kind}2x16", PACKING, MEDIUM, f"vec2 unpack{_kind}2x16(uint)")

# 8.5 Geometric functions.
_define("length", GEOMETRIC, EXPENSIVE, "float length(genType)")
_define("distance", GEOMETRIC, EXPENSIVE, "float distance(genType, genType)")
_define("dot", GEOMETRIC, MEDIUM, "float dot(genType, genType)")
_define("cross", GEOMETRIC, MEDIUM, "vec3 cross(vec3, vec3)")
_define("normalize", GEOMETRIC, EXPENSIVE, "genType normalize(genType)")
_define("faceforward", GEOMETRIC, MEDIUM, "genType faceforward(genType, genType, genType)")
_define("reflect", GEOMETRIC, MEDIUM, "genType reflect(genType, genType)")
_define("refract", GEOMETRIC, EXPENSIVE, "genType refract(genType, genType, float)")

# 8.6 Matrix functions.
_define("matrixCompMult", MATRIX, MEDIUM, "mat matrixCompMult(mat, mat)")
_define_explicit(
    "outerProduct",
    MATRIX,
    MEDIUM,  # matCxR outerProduct(vecR c, vecC r)
    lambda: [(m, (T.vector("float", m.rows), T.vector("float", m.cols))) for m in _MATS],
)
_define_explicit(
    "transpose", MATRIX, CHEAP, lambda: [(T.matrix(m.rows, m.cols), (m,)) for m in _MATS]
)
_define("determinant", MATRIX, MEDIUM, "float determinant(sqmat)")
_define("inverse", MATRIX, EXPENSIVE, "sqmat inverse(sqmat)")

# 8.7 Vector relational functions.
for _n in ("lessThan", "lessThanEqual", "greaterThan", "greaterThanEqual"):
    _define(
        _n,
        VECTOR_RELATIONAL,
        CHEAP,
        f"bvec {_n}(vec, vec)",
        f"bvec {_n}(ivec, ivec)",
        f"bvec {_n}(uvec, uvec)",
    )
for _n in ("equal", "notEqual"):
    _define(
        _n,
        VECTOR_RELATIONAL,
        CHEAP,
        f"bvec {_n}(vec, vec)",
        f"bvec {_n}(ivec, ivec)",
        f"bvec {_n}(uvec, uvec)",
        f"bvec {_n}(bvec, bvec)",
    )
_define("any", VECTOR_RELATIONAL, CHEAP, "bool any(bvec)")
_define("all", VECTOR_RELATIONAL, CHEAP, "bool all(bvec)")
_define("not", VECTOR_RELATIONAL, CHEAP, "bvec not(bvec)")

# 8.8 Texture lookup functions. "g" ranges over float/int/uint samplers and results.
_define(
    "textureSize",
    TEXTURE,
    CHEAP,
    "ivec2 textureSize(gsampler2D, int)",
    "ivec3 textureSize(gsampler3D, int)",
    "ivec2 textureSize(gsamplerCube, int)",
    "ivec2 textureSize(sampler2DShadow, int)",
    "ivec2 textureSize(samplerCubeShadow, int)",
    "ivec3 textureSize(gsampler2DArray, int)",
    "ivec3 textureSize(sampler2DArrayShadow, int)",
)
_define(
    "texture",
    TEXTURE,
    EXPENSIVE,
    "gvec4 texture(gsampler2D, vec2[, float bias])",
    "gvec4 texture(gsampler3D, vec3[, float bias])",
    "gvec4 texture(gsamplerCube, vec3[, float bias])",
    "float texture(sampler2DShadow, vec3[, float bias])",
    "float texture(samplerCubeShadow, vec4[, float bias])",
    "gvec4 texture(gsampler2DArray, vec3[, float bias])",
    "float texture(sampler2DArrayShadow, vec4)",
)
_define(
    "textureProj",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureProj(gsampler2D, vec3[, float bias])",
    "gvec4 textureProj(gsampler2D, vec4[, float bias])",
    "gvec4 textureProj(gsampler3D, vec4[, float bias])",
    "float textureProj(sampler2DShadow, vec4[, float bias])",
)
_define(
    "textureLod",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureLod(gsampler2D, vec2, float)",
    "gvec4 textureLod(gsampler3D, vec3, float)",
    "gvec4 textureLod(gsamplerCube, vec3, float)",
    "float textureLod(sampler2DShadow, vec3, float)",
    "gvec4 textureLod(gsampler2DArray, vec3, float)",
)
_define(
    "textureOffset",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureOffset(gsampler2D, vec2, ivec2[, float bias])",
    "gvec4 textureOffset(gsampler3D, vec3, ivec3[, float bias])",
    "float textureOffset(sampler2DShadow, vec3, ivec2[, float bias])",
    "gvec4 textureOffset(gsampler2DArray, vec3, ivec2[, float bias])",
)
_define(
    "texelFetch",
    TEXTURE,
    EXPENSIVE,
    "gvec4 texelFetch(gsampler2D, ivec2, int)",
    "gvec4 texelFetch(gsampler3D, ivec3, int)",
    "gvec4 texelFetch(gsampler2DArray, ivec3, int)",
)
_define(
    "texelFetchOffset",
    TEXTURE,
    EXPENSIVE,
    "gvec4 texelFetchOffset(gsampler2D, ivec2, int, ivec2)",
    "gvec4 texelFetchOffset(gsampler3D, ivec3, int, ivec3)",
    "gvec4 texelFetchOffset(gsampler2DArray, ivec3, int, ivec2)",
)
_define(
    "textureProjOffset",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureProjOffset(gsampler2D, vec3, ivec2[, float bias])",
    "gvec4 textureProjOffset(gsampler2D, vec4, ivec2[, float bias])",
    "gvec4 textureProjOffset(gsampler3D, vec4, ivec3[, float bias])",
    "float textureProjOffset(sampler2DShadow, vec4, ivec2[, float bias])",
)
_define(
    "textureLodOffset",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureLodOffset(gsampler2D, vec2, float, ivec2)",
    "gvec4 textureLodOffset(gsampler3D, vec3, float, ivec3)",
    "float textureLodOffset(sampler2DShadow, vec3, float, ivec2)",
    "gvec4 textureLodOffset(gsampler2DArray, vec3, float, ivec2)",
)
_define(
    "textureProjLod",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureProjLod(gsampler2D, vec3, float)",
    "gvec4 textureProjLod(gsampler2D, vec4, float)",
    "gvec4 textureProjLod(gsampler3D, vec4, float)",
    "float textureProjLod(sampler2DShadow, vec4, float)",
)
_define(
    "textureProjLodOffset",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureProjLodOffset(gsampler2D, vec3, float, ivec2)",
    "gvec4 textureProjLodOffset(gsampler2D, vec4, float, ivec2)",
    "gvec4 textureProjLodOffset(gsampler3D, vec4, float, ivec3)",
    "float textureProjLodOffset(sampler2DShadow, vec4, float, ivec2)",
)
_define(
    "textureGrad",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureGrad(gsampler2D, vec2, vec2, vec2)",
    "gvec4 textureGrad(gsampler3D, vec3, vec3, vec3)",
    "gvec4 textureGrad(gsamplerCube, vec3, vec3, vec3)",
    "float textureGrad(sampler2DShadow, vec3, vec2, vec2)",
    "float textureGrad(samplerCubeShadow, vec4, vec3, vec3)",
    "gvec4 textureGrad(gsampler2DArray, vec3, vec2, vec2)",
    "float textureGrad(sampler2DArrayShadow, vec4, vec2, vec2)",
)
_define(
    "textureGradOffset",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureGradOffset(gsampler2D, vec2, vec2, vec2, ivec2)",
    "gvec4 textureGradOffset(gsampler3D, vec3, vec3, vec3, ivec3)",
    "float textureGradOffset(sampler2DShadow, vec3, vec2, vec2, ivec2)",
    "gvec4 textureGradOffset(gsampler2DArray, vec3, vec2, vec2, ivec2)",
    "float textureGradOffset(sampler2DArrayShadow, vec4, vec2, vec2, ivec2)",
)
_define(
    "textureProjGrad",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureProjGrad(gsampler2D, vec3, vec2, vec2)",
    "gvec4 textureProjGrad(gsampler2D, vec4, vec2, vec2)",
    "gvec4 textureProjGrad(gsampler3D, vec4, vec3, vec3)",
    "float textureProjGrad(sampler2DShadow, vec4, vec2, vec2)",
)
_define(
    "textureProjGradOffset",
    TEXTURE,
    EXPENSIVE,
    "gvec4 textureProjGradOffset(gsampler2D, vec3, vec2, vec2, ivec2)",
    "gvec4 textureProjGradOffset(gsampler2D, vec4, vec2, vec2, ivec2)",
    "gvec4 textureProjGradOffset(gsampler3D, vec4, vec3, vec3, ivec3)",
    "float textureProjGradOffset(sampler2DShadow, vec4, vec2, vec2, ivec2)",
)

# 8.9 Fragment processing (derivative) functions.
for _n in ("dFdx", "dFdy", "fwidth"):
    _define(_n, DERIVATIVE, MEDIUM, f"genType {_n}(genType)", fragment_only=True)

#: Texture functions whose last ``offset`` argument must be a constant expression (spec 8.8).
CONSTANT_OFFSET_FUNCTIONS = frozenset(n for n in BUILTINS if n.endswith("Offset"))


def resolve(name: str, arg_types: list[Type]) -> Overload | str:
    """The overload of built-in ``name`` that takes exactly ``arg_types``, or an error message.

    GLSL ES 3.00 has no implicit conversions, so the match is exact.
    """
    fn = BUILTINS.get(name)
    if fn is None:
        return f"'{name}' is not a built-in function"
    args = tuple(arg_types)
    for ov in fn.overloads:
        if ov.params == args:
            return ov
    call = f"{name}({', '.join(str(a) for a in args)})"
    shown = list(fn.overloads)
    if len(shown) > _MAX_CANDIDATES:
        # Long lists (texture, min, ...): keep those that agree on what was given right.
        for keep in (
            lambda ov: ov.params[:1] == args[:1] != (),
            lambda ov: len(ov.params) == len(args),
        ):
            narrowed = [ov for ov in fn.overloads if keep(ov)]
            if narrowed:
                shown = narrowed
                break
    listed = ", ".join(ov.signature() for ov in shown[:_MAX_CANDIDATES])
    more = len(fn.overloads) - min(len(shown), _MAX_CANDIDATES)
    tail = f", ... and {more} more" if more else ""
    return f"no matching overload for '{call}'; candidates: {listed}{tail}"


_MAX_CANDIDATES = 24


def is_builtin_function(name: str) -> bool:
    return name in BUILTINS


# ---------------------------------------------------------------------------------------
# Built-in variables and constants of the fragment shader (spec 7.2 - 7.4).


class BuiltinVariable(namedtuple("BuiltinVariable", "name type storage value", defaults=(None,))):
    """A built-in variable: `name`, its `type` (Type), `storage`: "in" (read-only input),
    "out" (write-only output), "const" or "uniform"; `value`: a constant's value (the spec's
    minimum maximum), else None. (collections.namedtuple: typing's NamedTuple would import
    typing at every start-up.)"""

    __slots__ = ()


GL_DEPTH_RANGE_PARAMETERS = StructType(
    "gl_DepthRangeParameters", (("near", T.FLOAT), ("far", T.FLOAT), ("diff", T.FLOAT))
)

_CONSTANTS = {
    "gl_MaxVertexAttribs": 16,
    "gl_MaxVertexUniformVectors": 256,
    "gl_MaxVertexOutputVectors": 16,
    "gl_MaxFragmentInputVectors": 15,
    "gl_MaxVertexTextureImageUnits": 16,
    "gl_MaxCombinedTextureImageUnits": 32,
    "gl_MaxTextureImageUnits": 16,
    "gl_MaxFragmentUniformVectors": 224,
    "gl_MaxDrawBuffers": 4,
    "gl_MinProgramTexelOffset": -8,
    "gl_MaxProgramTexelOffset": 7,
}

BUILTIN_VARIABLES: dict[str, BuiltinVariable] = {
    v.name: v
    for v in [
        BuiltinVariable("gl_FragCoord", T.VEC4, "in"),
        BuiltinVariable("gl_FrontFacing", T.BOOL, "in"),
        BuiltinVariable("gl_PointCoord", T.VEC2, "in"),
        BuiltinVariable("gl_FragDepth", T.FLOAT, "out"),
        BuiltinVariable("gl_DepthRange", GL_DEPTH_RANGE_PARAMETERS, "uniform"),
        *(BuiltinVariable(n, T.INT, "const", v) for n, v in _CONSTANTS.items()),
    ]
}


# ---------------------------------------------------------------------------------------
# What Shadertoy declares before a tab.


class Uniform(namedtuple("Uniform", "type array_size comment")):
    """A Shadertoy uniform: `type` (Type; the element type for arrays), `array_size` (int or
    None), `comment`."""

    __slots__ = ()

    @property
    def declared_type(self) -> Type:
        """The full type of the name: ``float[4]`` for ``iChannelTime``."""
        return self.type if self.array_size is None else ArrayType(self.type, self.array_size)


# The uniforms come from the one table of what Shadertoy declares (glslcheck/shadertoy/wrapper.py,
# which the GL wrapper and both renderers use too), typed here for the checker.
SHADERTOY_UNIFORMS: dict[str, Uniform] = {
    u.name: Uniform(T.BY_NAME[u.glsl_type], u.array_size, u.doc) for u in _SHADERTOY_TABLE
}

#: The only uniforms declared when Shadertoy compiles the Common tab on its own.
COMMON_TAB_UNIFORMS = frozenset(_COMMON_ONLY)


# ---------------------------------------------------------------------------------------
# Keywords and reserved words (spec 3.8).

KEYWORDS = frozenset(
    """
    const uniform layout centroid flat smooth break continue do for while switch case default
    if else in out inout float int void bool true false invariant discard return
    mat2 mat3 mat4 mat2x2 mat2x3 mat2x4 mat3x2 mat3x3 mat3x4 mat4x2 mat4x3 mat4x4
    vec2 vec3 vec4 ivec2 ivec3 ivec4 bvec2 bvec3 bvec4 uint uvec2 uvec3 uvec4
    lowp mediump highp precision
    sampler2D sampler3D samplerCube sampler2DShadow samplerCubeShadow sampler2DArray
    sampler2DArrayShadow isampler2D isampler3D isamplerCube isampler2DArray
    usampler2D usampler3D usamplerCube usampler2DArray struct
""".split()
)

#: Reserved for future use: using one as an identifier is an error.
RESERVED_WORDS = frozenset(
    """
    attribute varying coherent volatile restrict readonly writeonly resource atomic_uint
    noperspective patch sample subroutine common partition active asm class union enum
    typedef template this goto inline noinline public static extern external interface
    long short double half fixed unsigned superp input output
    hvec2 hvec3 hvec4 dvec2 dvec3 dvec4 fvec2 fvec3 fvec4 sampler3DRect filter
    image1D image2D image3D imageCube iimage1D iimage2D iimage3D iimageCube
    uimage1D uimage2D uimage3D uimageCube image1DArray image2DArray
    iimage1DArray iimage2DArray uimage1DArray uimage2DArray imageBuffer iimageBuffer
    uimageBuffer sampler1D sampler1DShadow sampler1DArray sampler1DArrayShadow
    isampler1D isampler1DArray usampler1D usampler1DArray sampler2DRect sampler2DRectShadow
    isampler2DRect usampler2DRect samplerBuffer isamplerBuffer usamplerBuffer
    sampler2DMS isampler2DMS usampler2DMS sampler2DMSArray isampler2DMSArray
    usampler2DMSArray sizeof cast namespace using
""".split()
)
