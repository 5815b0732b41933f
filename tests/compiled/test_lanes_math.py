"""backends/compiled_engine/lanes_math.py against scalar.py: the same bits for every input, and
straight-line code that LLVM's SLP vectoriser turns into packed (W-wide) instructions.

Each function of lanes_math runs here as the lockstep engine calls it: W = 8 pixels' values in a
tuple, ``(f(a[0], ...), ..., f(a[7], ...))``, in a loop over blocks, with ``FMA`` a compile-time
constant (the generated module's global); scalar.py's runs one lane at a time. Arguments: random
float32/int32 bit patterns, the ranges shaders use, and every pair of special values (zeros of
both signs, infinities, NaNs with several payloads and signs, subnormals, |x| around 2**29,
2**31, 2**32, FLT_MAX, the exp2 clamp's ends, quadrant boundaries of sin).

numba is the `jit` extra: these tests skip without it on a developer machine and fail on CI
(the `numba` fixture, tests/conftest.py).
"""

from __future__ import annotations

import re

import numpy as np
import pytest

W = 8
N_RANDOM = (
    600_000  # per kind of argument; with the ranges and the special pairs ~2.5M lanes a function
)

# name: (argument kinds, result kind, takes fma); f float32, i int32, u uint32
SPECS = {
    "fmin": ("ff", "f", False),
    "fmax": ("ff", "f", False),
    "clamp": ("fff", "f", False),
    "sign": ("f", "f", False),
    "daz": ("f", "f", False),
    "mix_fast": ("fff", "f", False),
    "idiv": ("ii", "i", False),
    "udiv": ("uu", "u", False),
    "irem": ("ii", "i", False),
    "urem": ("uu", "u", False),
    "irem_const": ("ii", "i", False),
    "to_int": ("f", "i", False),
    "to_uint_sse": ("f", "u", False),
    "to_uint_avx512": ("f", "u", False),
    "to_uint_arm64": ("f", "u", False),
    "sin": ("f", "f", True),
    "cos": ("f", "f", True),
    "tan": ("f", "f", True),
    "exp2": ("f", "f", True),
    "log2": ("f", "f", True),
    "pow": ("ff", "f", True),
    "pow_zero": ("f", "f", False),
    "exp": ("f", "f", True),
    "log": ("f", "f", True),
    "asin": ("f", "f", False),
    "acos": ("f", "f", False),
    "atan": ("f", "f", False),
    "atan2": ("ff", "f", False),
    "sinh": ("f", "f", True),
    "cosh": ("f", "f", True),
    "tanh": ("f", "f", True),
    "asinh": ("f", "f", True),
    "acosh": ("f", "f", True),
    "atanh": ("f", "f", True),
    # scalar.py's own, which vectorise as they are (lanes_math.AS_IS)
    "fract": ("f", "f", False),
    "mod": ("ff", "f", False),
    "step": ("ff", "f", False),
    "smoothstep": ("fff", "f", False),
    "smoothstep_scaled": ("ffff", "f", False),
    "inversesqrt": ("f", "f", False),
    "ishl": ("ii", "i", False),
    "ishr": ("ii", "i", False),
    "ushl": ("uu", "u", False),
    "ushr": ("uu", "u", False),
    "iabs": ("i", "i", False),
    "isign": ("i", "i", False),
    "float_bits_to_int": ("f", "i", False),
    "float_bits_to_uint": ("f", "u", False),
    "int_bits_to_float": ("i", "f", False),
    "uint_bits_to_float": ("u", "f", False),
    "round_even": ("f", "f", False),
}
DTYPES = {"f": np.float32, "i": np.int32, "u": np.uint32}

_SPECIAL_BITS = [
    0x00000000,
    0x7FC00000,
    0xFFC00000,
    0x7FC12345,
    0xFF812345,
    0x7F800001,  # 0, NaNs (quiet, signalling)
    0x7F800000,
    0x00000001,
    0x007FFFFF,
    0x00800000,
    0x7F7FFFFF,
    0x3F800000,
    0x3F000000,  # Inf, subnormals, FLT_MIN, MAX, 1, .5
    0x4E000000,
    0x4DFFFFFF,
    0x4F000000,
    0x4EFFFFFF,
    0x4F800000,
    0x4F7FFFFF,
    0x5F800000,  # 2**29, 2**31, 2**32, 2**64
    0x42FE0000,
    0x42FDFFFF,
    0x43000000,
    0x43010000,
    0x41200000,
    0x5D5E0B6B,
    0x7F000000,
]  # 127, 126.99999, 128, 129, 10, 1e18, 2**127
_SPECIAL_FLOATS = [
    np.pi / 4,
    np.pi / 2,
    np.pi,
    3 * np.pi / 2,
    2 * np.pi,
    100.0,
    3e38,
    1e-3,
    0.7853982,
    2.356194,
]


def _special_floats() -> np.ndarray:
    pos = np.concatenate(
        [np.array(_SPECIAL_BITS, np.uint32).view(np.float32), np.array(_SPECIAL_FLOATS, np.float32)]
    )
    with np.errstate(over="ignore", invalid="ignore"):
        pos = np.concatenate(
            [pos, np.nextafter(pos, np.float32(np.inf)), np.nextafter(pos, np.float32(0))]
        )
    return np.concatenate([pos, -pos])  # -NaN of each NaN: the sign bit flipped


def _special_ints(dtype) -> np.ndarray:
    v = [
        0,
        1,
        2,
        3,
        7,
        31,
        32,
        33,
        100,
        2**31 - 1,
        2**31,
        2**31 + 1,
        2**32 - 1,
        2**32 - 2,
        2**16,
        2**30,
    ]
    return (
        np.array([x % 2**32 for x in v] + [(-x) % 2**32 for x in v], np.uint64)
        .astype(np.uint32)
        .view(dtype)
    )


def _column(rng, kind: str, n: int) -> np.ndarray:
    """n arguments of one kind: random bit patterns, then the ranges shaders use."""
    bits = rng.integers(0, 2**32, n, dtype=np.uint64).astype(np.uint32)
    if kind != "f":
        small = rng.integers(-100, 101, n).astype(np.int64) % 2**32
        return np.concatenate([bits, small.astype(np.uint32)]).view(DTYPES[kind])
    ranges = [
        rng.uniform(-1, 1, n),
        rng.uniform(-100, 100, n),
        rng.uniform(-2e4, 2e4, n // 4),
        rng.uniform(-130, 130, n // 4),
        np.exp(rng.uniform(-80, 80, n // 4)) * rng.choice([-1, 1], n // 4),
    ]
    return np.concatenate([bits.view(np.float32)] + [r.astype(np.float32) for r in ranges])


def arguments(kinds: str, seed: int = 18) -> list[np.ndarray]:
    """One array per argument, the same length (a multiple of W): each argument random on its own,
    then every combination of the special values of the argument kinds (for three arguments,
    every pair with the third random)."""
    rng = np.random.default_rng(seed)
    cols = [_column(rng, k, N_RANDOM) for k in kinds]
    n = min(c.size for c in cols)
    cols = [rng.permutation(c)[:n] for c in cols]
    specials = [_special_floats() if k == "f" else _special_ints(DTYPES[k]) for k in kinds]
    if len(kinds) == 1:
        cols = [np.concatenate([cols[0], specials[0]])]
    else:
        grid = np.meshgrid(specials[0], specials[1], indexing="ij")
        pair = [g.ravel() for g in grid]
        extra = [rng.choice(_column(rng, k, 1000), pair[0].size) for k in kinds[2:]]
        cols = [np.concatenate([c, p]) for c, p in zip(cols, pair + extra)]
    pad = -cols[0].size % W
    return [np.ascontiguousarray(np.concatenate([c, c[:pad]])) for c in cols]


def _source(
    nargs: int, fma: bool | None, extra: str = "", loop: bool = True, params: str = ""
) -> str:
    """A numba function ``k(x0, ..., out)``: the W-lane tuple form of ``f`` over blocks, or on
    the first block only (straight-line code: what the vectorisation tests read). ``params``
    (``", s, z"``) are more arguments of k, the same for every lane (``extra`` can pass them)."""
    xs = [f"x{k}" for k in range(nargs)]
    head = [f"    for b in range(out.size // {W}):"] if loop else ["    if out.size >= W:"]
    lines = (
        [f"def k({', '.join(xs)}{params}, out):"]
        + head
        + [f"    \ti = np.uint64(b * {W})" if loop else "    \ti = 0"]
    )
    for x in xs:
        lines.append(
            f"    \t{x}_ = (" + ", ".join(f"{x}[i + np.uint64({j})]" for j in range(W)) + ",)"
        )
    tail = extra + (", FMA" if fma is not None else "")
    calls = [f"f({', '.join(f'{x}_[{j}]' for x in xs)}{tail})" for j in range(W)]
    lines.append("    \tr = (" + ", ".join(calls) + ",)")
    lines += [f"    \tout[i + np.uint64({j})] = r[{j}]" for j in range(W)]
    if not loop:
        lines = [line.replace("i + np.uint64(", "(") for line in lines]
    return "\n".join(lines).replace("    \t", "        ")


def lanes_kernel(
    module, name: str, fma: bool | None, extra: str = "", loop: bool = True, params: str = ""
):
    import numba

    kinds, _, _ = SPECS.get(name, ("ff", "f", True))
    g = {"f": getattr(module, name), "np": np, "FMA": fma, "W": W}
    exec(_source(len(kinds), fma, extra, loop, params), g)
    return numba.njit(error_model="numpy")(g["k"])


def reference_kernel(scalar, name: str, extra: str = ""):
    """scalar.py's ``name`` one lane at a time; ``fma`` a run-time argument."""
    import numba

    kinds, _, takes_fma = SPECS.get(name, ("ff", "f", True))
    xs = ", ".join(f"x{k}" for k in range(len(kinds)))
    args = ", ".join(f"x{k}[k]" for k in range(len(kinds))) + extra + (", fma" if takes_fma else "")
    src = f"def k(fma, {xs}, out):\n    for k in range(out.size):\n        out[k] = f({args})\n"
    g = {"f": getattr(scalar, name)}
    exec(src, g)
    return numba.njit(error_model="numpy")(g["k"])


@pytest.fixture(scope="module")
def slp(numba):
    """numba's SLP vectoriser on while this module compiles its kernels (off by default)."""
    from numba.core import config

    old = config.SLP_VECTORIZE
    config.SLP_VECTORIZE = 1
    yield
    config.SLP_VECTORIZE = old


@pytest.fixture(scope="module")
def modules(numba):
    from glslcheck.backends.compiled_engine import lanes_math, scalar

    return scalar, lanes_math


def _open_nan_choice(args: list[np.ndarray], want: np.ndarray, got: np.ndarray) -> np.ndarray:
    """Where two or more float arguments are NaN and both results are NaN with the quiet payload
    of one of them: IEEE 754 (6.2.3) leaves open which input NaN's payload an operation keeps,
    and x86 keeps its first operand's, so it is LLVM's operand order (it commutes fmul and fadd
    as it packs lanes) that decides, not our code. mix_fast(x, NaN, sNaN) kept y's payload in
    the W-lane tuple and a's in scalar.py on an AMD EPYC (AVX-512)."""
    floats = [a for a in args if a.dtype == np.float32]
    if want.dtype != np.float32 or len(floats) < 2:
        return np.zeros(want.size, bool)
    nans = sum(np.isnan(a).astype(int) for a in floats)
    quiet = [a.view(np.uint32) | np.uint32(0x00400000) for a in floats]
    g = got.view(np.uint32)
    own = np.zeros(want.size, bool)
    for q in quiet:
        own |= g == q
    return (nans >= 2) & np.isnan(want) & np.isnan(got) & own


def _assert_same_bits(name: str, args: list[np.ndarray], want: np.ndarray, got: np.ndarray) -> None:
    differ = want.view(np.uint32) != got.view(np.uint32)
    bad = np.flatnonzero(differ & ~_open_nan_choice(args, want, got))
    if bad.size:
        k = bad[0]
        shown = ", ".join(f"{a[k]!r} (0x{a[k : k + 1].view(np.uint32)[0]:08x})" for a in args)
        pytest.fail(
            f"{name}: {bad.size} of {want.size} results differ; first: {name}({shown}) = "
            f"0x{got[k : k + 1].view(np.uint32)[0]:08x}, scalar.py "
            f"0x{want[k : k + 1].view(np.uint32)[0]:08x}"
        )


def _rewritten_cases():
    from glslcheck.backends.compiled_engine.lanes_math import REWRITTEN

    for name in REWRITTEN:
        if name == "pow_uniform":
            continue
        for fma in (True, False) if SPECS[name][2] else (None,):
            yield pytest.param(
                name,
                fma,
                id=f"{name}-{'fma' if fma else 'nofma' if fma is False else ''}".rstrip("-"),
            )


@pytest.mark.parametrize("name,fma", list(_rewritten_cases()))
def test_same_bits_as_scalar(slp, modules, name, fma):
    scalar, lanes = modules
    kinds, out_kind, _ = SPECS[name]
    args = arguments(kinds)
    want = np.empty(args[0].size, DTYPES[out_kind])
    got = np.empty_like(want)
    reference_kernel(scalar, name)(bool(fma), *args, want)
    lanes_kernel(lanes, name, fma)(*args, got)
    _assert_same_bits(name, args, want, got)


@pytest.mark.parametrize("flags", ["constant", "run-time"])
@pytest.mark.parametrize(
    "special,zeros,fma",
    [(True, True, True), (True, False, True), (False, False, True), (False, False, False)],
)
def test_pow_uniform_same_bits(slp, modules, special, zeros, fma, flags):
    """pow_uniform's exponent: +0 where ``zeros``, one of 0, 1, 2, 4 where ``special``, else any.
    The flags as constants (folded) and as the kernel's arguments, as the generated code passes
    them for a uniform exponent that is not a constant."""
    scalar, lanes = modules
    x, y = arguments("ff")
    if special:
        y = (
            np.zeros_like(y)
            if zeros
            else np.random.default_rng(5).choice(np.float32([0, 1, 2, 4]), y.size)
        )
    want = np.empty_like(x)
    got = np.empty_like(x)
    extra = f", {special}, {zeros}"
    reference_kernel(scalar, "pow_uniform", extra)(fma, x, y, want)
    if flags == "constant":
        lanes_kernel(lanes, "pow_uniform", fma, extra)(x, y, got)
    else:
        lanes_kernel(lanes, "pow_uniform", fma, ", s, z", params=", s, z")(
            x, y, special, zeros, got
        )
    _assert_same_bits("pow_uniform", [x, y], want, got)


SHININESS = """
float specular(in vec3 n, in vec3 v, in float shininess)
{
    float s = 0.0;
    for (int i = 0; i < 4; ++i)
    {
        vec3 h = normalize(normalize(vec3(float(i) - 1.5, 1.0, 2.0)) + v);
        s += pow(max(dot(n, h), 0.0), shininess);
    }
    return s;
}
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 n = normalize(vec3((fragCoord + fragCoord - iResolution.xy) / iResolution.y, 1.0));
    fragColor = vec4(vec3(specular(n, vec3(0.0, 0.0, 1.0), 24.0)), 1.0);
}
"""


def test_pow_of_a_uniform_parameter_is_packed(avx2, make_shader):
    """``pow(x, shininess)``, shininess a parameter the same for every lane (not a constant: the
    generated code calls pow_uniform with run-time flags), in a loop as Lab 4's light sums have
    it: the lockstep function's machine code is mostly packed. With an ``if`` on the flags in
    pow_uniform, each of its W inlined copies was blocks of its own, which the SLP vectoriser
    (it packs within a block) left scalar: 9 packed and 311 scalar instructions, 41 jumps, on an
    AMD EPYC (znver4); by selects 60 packed, 21 scalar, 1 jump. A W-lane tuple of pow_uniform
    alone in a small kernel was packed either way (LLVM merged the W branches there), so this
    test reads a generated module. It is compiled without numba's cache (numba shows no machine
    code for a function it loaded from there)."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    def report(text: str, call: str) -> dict:
        source, path = generate(make_shader(text), lanes=W)
        assert call in source and "cache=True" in source
        mod = CompiledProgram(source.replace("cache=True", "cache=False"), path).load()
        name = next(n for n in dir(mod) if n.startswith("f_specular__"))
        return vector_report(getattr(mod, name), name)

    got = report(SHININESS, "pow_uniform(")
    # the same function with a product for the pow: the jumps the loop's own bookkeeping takes
    # (its condition, LOOP_CAP, llvmpipe's pass budget: once a block, whatever W), which the
    # pow's must not add to by one a lane
    loop = report(
        SHININESS.replace("pow(max(dot(n, h), 0.0), shininess)", "dot(n, h) * shininess"), ""
    )
    assert got["packed"] > got["scalar"] and got["jumps"] - loop["jumps"] < W, (got, loop)


def test_lists_cover_scalar(modules):
    """Every public numba function of scalar.py is either rewritten here or vectorises as it is
    (except the array helpers, index and the loop budget's, which a lockstep engine does not
    call per lane)."""
    scalar, lanes = modules
    import numba

    public = {
        n
        for n, v in vars(scalar).items()
        if isinstance(v, numba.core.registry.CPUDispatcher)
        and not n.startswith("_")
        and v.py_func.__module__ == scalar.__name__
    } | {"fmin", "fmax"}
    listed = set(lanes.REWRITTEN) | set(lanes.AS_IS)
    block = {"tick", "tick_end", "limited", "loops_limited"}  # the loop budget: once a block
    left = public - listed - block - {"acopy", "aslice", "aset", "index", "pow_special"}
    assert not left, f"scalar.py functions in neither list: {sorted(left)}"
    assert listed <= public
    for name in lanes.REWRITTEN:
        assert getattr(lanes, name) is not getattr(scalar, name)


# -- vectorisation --------------------------------------------------------------------------
# The kernel is one block, no loop (LLVM's loop vectoriser would add its own vector loop and
# remainder). A function that runs its W lanes one at a time needs at least W scalar instructions
# for its arithmetic (one a lane), a branch on a lane's value at least W conditional jumps, and a
# call that LLVM did not inline W calls. So the machine code of the W-lane kernel is vectorised when
# it has packed (xmm or ymm) arithmetic (or, for a reinterpretation of bits, 8-lane moves), fewer
# than W scalar arithmetic instructions, fewer than W conditional jumps and no call. No exact count
# is pinned: the instructions LLVM chooses depend on the CPU and LLVM's release.
_ARITH = (
    r"(?:add|sub|mul|div|sqrt|min|max|round|fn?m(?:add|sub)\w*|"
    r"cmp\w*|and|andn|or|xor|blendv|cvt\w*)"
)
_PACKED = re.compile(
    rf"\tv{_ARITH}p[sd]\t[^\n]*%[xy]mm|\tvp\w+\t[^\n]*%[xy]mm|\tvmov(?:up[sd]|dq[au])\t[^\n]*%ymm"
)
_SCALAR = re.compile(rf"\tv{_ARITH}s[sd]\t|\tv?cvt\w*2si\w*\t")


def _host_avx2() -> str | None:
    """Why packed ymm code cannot be expected here, or None: LLVM targets the host CPU
    (numba's default); without AVX2 it has no 8-wide float32 or integer instructions."""
    import platform

    import llvmlite.binding as ll
    from numba.core import config

    if platform.machine() not in ("x86_64", "AMD64"):
        return f"not an x86-64 CPU ({platform.machine()}): no ymm registers"
    if config.CPU_NAME not in (None, "host"):
        return f"numba targets CPU {config.CPU_NAME!r} (NUMBA_CPU_NAME), not this machine's"
    if "+avx2" not in ll.get_host_cpu_features().flatten():
        return "this CPU has no AVX2: LLVM emits 4-wide SSE (xmm) code or none"
    return None


def _body(kernel, name: str = "k") -> str:
    """The machine code of numba function ``name`` (its mangled name: length, then name)."""
    asm = next(iter(kernel.inspect_asm().values()))
    m = re.search(
        rf"^(_ZN(?!7cpython)\w*{len(name)}{name}\w*):\n(.*?)\.Lfunc_end", asm, re.S | re.M
    )
    assert m, f"{name}'s machine code was not found in numba's assembly"
    return m.group(2)


def vector_report(kernel, name: str = "k") -> dict[str, int]:
    body = _body(kernel, name)
    return {
        "packed": len(_PACKED.findall(body)),
        "scalar": len(_SCALAR.findall(body)),
        "jumps": len(re.findall(r"\tj(?!mp)\w+\t", body)),
        "calls": len(re.findall(r"\tcall", body)),
    }


def _vectorised(report: dict[str, int]) -> bool:
    return (
        report["packed"] > 0
        and report["scalar"] < W
        and report["jumps"] < W
        and report["calls"] == 0
    )


@pytest.fixture(scope="module")
def avx2(numba):
    why = _host_avx2()
    if why:
        pytest.skip(why)


@pytest.mark.parametrize("name", [n for n in SPECS if n != "pow_uniform"])
def test_w_lanes_vectorise(slp, avx2, modules, name):
    """The W-lane tuple of each lanes_math function (its rewritten ones and scalar's that it
    keeps) compiles to packed instructions, FMA a constant."""
    scalar, lanes = modules
    kinds, out_kind, takes_fma = SPECS[name]
    kernel = lanes_kernel(
        lanes if name in lanes.REWRITTEN else scalar, name, True if takes_fma else None, loop=False
    )
    args = arguments(kinds)
    kernel(*[a[:64] for a in args], np.empty(64, DTYPES[out_kind]))
    report = vector_report(kernel)
    assert _vectorised(report), f"{name}: {report}"


@pytest.mark.parametrize("name", ["sin", "idiv", "exp2"])
def test_scalar_versions_do_not_vectorise(slp, avx2, modules, name):
    """The check above can fail: scalar.py's branching versions in the same W-lane form.

    Functions whose branches LLVM cannot turn into selects (a loop-free reduction with calls, a
    division guarded by a branch, a table clamp): scalar.fmin's two NaN tests are no control,
    LLVM if-converts them on some CPUs (packed, one jump, on an AMD EPYC, znver4) and not on
    others."""
    scalar, _ = modules
    kinds, out_kind, takes_fma = SPECS[name]
    kernel = lanes_kernel(scalar, name, True if takes_fma else None, loop=False)
    args = arguments(kinds)
    kernel(*[a[:64] for a in args], np.empty(64, DTYPES[out_kind]))
    report = vector_report(kernel)
    assert not _vectorised(report), f"{name}: {report}"
