"""What the driver returns where GLSL ES 3.00 leaves a value undefined and the CPU decides.

GLSL ES 3.00 (section 4.1.10, "Conversions") leaves ``uint(f)`` undefined when ``f`` is negative,
NaN or too large for a uint. Mesa's llvmpipe turns ``uint(f)`` into LLVM's ``fptoui``, and LLVM
lowers that with whatever instructions the host CPU has, so the answer changes with the machine:

``avx512``  x86-64 with AVX-512F and AVX-512VL: one ``vcvttps2udq``. Truncates; a result outside
            ``[0, 2**32)`` and NaN give ``0xFFFFFFFF``; ``uint(-0.5)`` is 0 (``trunc(-0.5)`` is -0).
            Recorded on such a machine with tests/numpy/test_runtime_gl.py.
``sse``     x86-64 without AVX-512 (SSE2 ... AVX2): two signed ``cvttps2dq``, of ``f`` and of
            ``f - 2**31`` with the top bit then set, the second chosen where ``f >= 2**31``; the
            signed conversion gives ``0x80000000`` for NaN and for anything outside the int
            range. So ``uint(-3.5)`` is ``0xFFFFFFFD`` (-3 reinterpreted), ``uint(NaN)`` and
            ``uint(5e9)`` are ``0x80000000``. Measured on an AMD EPYC with AVX2, Mesa 22.3.6,
            LLVM 15.0.6.
``arm64``   AArch64's ``fcvtzu`` saturates: negatives and NaN give 0, too large ``0xFFFFFFFF``
            (the Arm architecture manual; not measured here, no such machine was at hand).

The other value the CPU decides is the rounding of gallivm's polynomials, whose multiply-adds
are fused only where the CPU has FMA (`host_fma`).

``int(f)`` is the same on every x86-64 CPU (``cvttps2dq``: ``0x80000000`` for NaN and out of
range) and is not listed here.

The NumPy backend's float32 mode copies more than these values: llvmpipe's sin, exp2, log2, atan
and texture filtering, and Mesa's rewrites of the arithmetic (nir_opt_algebraic, nir_lower_flrp),
from one Mesa release, `EMULATED_MESA`. Another Mesa may compute other bits, and another driver
surely does; `emulation_note` says so for `glslcheck verify` instead of letting a difference
read as a transpiler bug, and the bit-exact tests under tests/gl fail naming the release.

The NumPy backend cannot ask the CPU which instructions llvmpipe picked, so it predicts the model
from the CPU's flags (`host_model`), and `glslcheck verify`, which has the driver at hand,
measures it once per GL context (`measure` renders `PROBE_INPUTS` and `identify` names the model
that reproduces them) and has the NumPy side emulate that. The tests check each model against
its recorded table on every machine, and the live driver against the model it is identified as.
"""

from __future__ import annotations

import functools
import platform

import numpy as np

# float inputs whose uint conversion tells the models apart (and the in-range ones they share)
PROBE_INPUTS: tuple[float, ...] = (
    3.7,
    -0.5,
    -0.99,
    -1.0,
    -3.5,
    -1e9,
    -2147483648.0,
    -3e9,
    -5e9,
    5e9,
    3e9,
    4294967040.0,
    4294967296.0,
    2147483648.0,
    2147483520.0,
    float("nan"),
    float("inf"),
    float("-inf"),
    1e20,
    -1e20,
)

_TWO31 = 2.0**31
_INT_MIN_BITS = 0x80000000


def _signed_cvtt(t: np.ndarray) -> np.ndarray:
    """x86 ``cvttps2dq`` of already truncated float64 values, as uint32 bits: out of the int32
    range and NaN give 0x80000000."""
    ok = (t >= -_TWO31) & (t < _TWO31)  # False for NaN
    return np.where(ok, t, -_TWO31).astype(np.int64).astype(np.uint32)


def _avx512(x: np.ndarray) -> np.ndarray:
    t = np.trunc(x)
    ok = (t >= 0.0) & (t < 2.0**32)
    return np.where(ok, t, 0xFFFFFFFF).astype(np.int64).astype(np.uint32)


def _sse(x: np.ndarray) -> np.ndarray:
    # x - 2**31 is exact in float32 for x in [2**31, 2**32), so float64 gives the same bits
    high = _signed_cvtt(np.trunc(x - _TWO31)) | np.uint32(_INT_MIN_BITS)
    low = _signed_cvtt(np.trunc(x))
    return np.where(x >= _TWO31, high, low).astype(np.uint32)


def _arm64(x: np.ndarray) -> np.ndarray:
    t = np.trunc(np.nan_to_num(x, nan=0.0, posinf=2.0**32, neginf=0.0))
    return np.clip(t, 0.0, 2.0**32 - 1).astype(np.uint32)


# name -> uint32 bits of uint(x) for a float64 array x (float32 values, widened exactly)
FLOAT_TO_UINT = {"avx512": _avx512, "sse": _sse, "arm64": _arm64}


def float_to_uint(x: np.ndarray, model: str) -> np.ndarray:
    """``uint(x)`` as the named model computes it; x is a float array (any float dtype)."""
    with np.errstate(invalid="ignore", over="ignore"):
        return FLOAT_TO_UINT[model](np.asarray(x, dtype=np.float64))


def _cpu_flags() -> set[str]:
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


@functools.lru_cache(maxsize=1)
def host_model() -> str:
    """The model llvmpipe uses on this machine, predicted from the CPU (see the module doc)."""
    machine = platform.machine().lower()
    if machine in ("aarch64", "arm64"):
        return "arm64"
    flags = _cpu_flags()
    if {"avx512f", "avx512vl"} <= flags:
        return "avx512"
    return "sse"


@functools.lru_cache(maxsize=1)
def host_fma() -> bool:
    """True when this CPU fuses LLVM's ``llvm.fmuladd``, which gallivm's polynomials (sin, exp2,
    log2, ...) use: the x86 ``fma`` flag; aarch64 and ppc64le always fuse. Without FMA those
    built-ins round twice and about 1% of sin values move by one ULP."""
    machine = platform.machine().lower()
    if machine not in ("x86_64", "amd64", "i386", "i686"):
        return machine in ("aarch64", "arm64", "ppc64le", "ppc64")
    return "fma" in _cpu_flags()


def identify(measured: dict[float, int] | list[int]) -> str | None:
    """The model that reproduces a measurement of `PROBE_INPUTS` (uint32 bits, in order, or a
    mapping input -> bits), or None when none does."""
    if isinstance(measured, dict):
        inputs = np.array(list(measured), dtype=np.float64)
        bits = [int(v) & 0xFFFFFFFF for v in measured.values()]
    else:
        inputs = np.array(PROBE_INPUTS, dtype=np.float64)
        bits = [int(v) & 0xFFFFFFFF for v in measured]
    for name in FLOAT_TO_UINT:
        if float_to_uint(inputs, name).tolist() == bits:
            return name
    return None


_PROBE_FS = """#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
uniform sampler2D inputs;
out uvec4 o;
void main() { o = uvec4(uint(texelFetch(inputs, ivec2(gl_FragCoord.xy), 0).x), 0u, 0u, 0u); }
"""
_PROBE_VS = "#version 300 es\nin vec2 p;\nvoid main() { gl_Position = vec4(p, 0.0, 1.0); }\n"


def measure(ctx) -> list[int]:
    """uint(x) of every `PROBE_INPUTS` value as the driver of moderngl context `ctx` computes it
    while shading (inputs come from an R32F texture, so the compiler cannot fold them)."""
    import moderngl

    n = len(PROBE_INPUTS)
    objects = []
    try:
        prog = ctx.program(vertex_shader=_PROBE_VS, fragment_shader=_PROBE_FS)
        vbo = ctx.buffer(np.array([-1, -1, 3, -1, -1, 3], dtype="f4").tobytes())
        vao = ctx.simple_vertex_array(prog, vbo, "p")
        src = ctx.texture((n, 1), 1, data=np.array(PROBE_INPUTS, dtype="f4").tobytes(), dtype="f4")
        src.filter = (moderngl.NEAREST, moderngl.NEAREST)
        out = ctx.texture((n, 1), 4, dtype="u4")
        fbo = ctx.framebuffer([out])
        objects = [vao, fbo, out, src, vbo, prog]
        src.use(0)
        if "inputs" in prog:
            prog["inputs"].value = 0
        fbo.use()
        fbo.viewport = (0, 0, n, 1)
        vao.render()
        data = np.frombuffer(fbo.read(components=4, dtype="u4"), dtype="<u4").reshape(n, 4)
        return [int(v) for v in data[:, 0]]
    finally:
        for obj in objects:
            obj.release()


# The Mesa release whose llvmpipe the float32 NumPy emulation copies bit for bit (measured with
# Mesa 22.3.6 and LLVM 15.0.6, Debian 12): its algorithms are quoted from that release's source.
EMULATED_MESA = "22.3"


def driver_name(ctx) -> tuple[str, str | None]:
    """(GL_RENDERER, Mesa version or None) of a moderngl context: ``("llvmpipe (LLVM 15.0.6,
    256 bits)", "22.3.6")`` from GL_VERSION ``"4.5 (Core Profile) Mesa 22.3.6"``."""
    info = ctx.info
    version = str(info.get("GL_VERSION", ""))
    words = version.split()
    mesa = words[words.index("Mesa") + 1] if "Mesa" in words[:-1] else None
    return str(info.get("GL_RENDERER", "")), mesa


def is_emulated(renderer: str, mesa: str | None) -> bool:
    """True when the driver is the llvmpipe of `EMULATED_MESA` (any patch release)."""
    return (
        renderer.startswith("llvmpipe")
        and mesa is not None
        and (mesa == EMULATED_MESA or mesa.startswith(EMULATED_MESA + "."))
    )


def emulation_note(ctx) -> str | None:
    """None for the driver the NumPy backend emulates; else one line saying which driver this
    is and that differences in the last bits may be the driver's, not bugs."""
    renderer, mesa = driver_name(ctx)
    if is_emulated(renderer, mesa):
        return None
    driver = f"{renderer}, Mesa {mesa}" if mesa else renderer
    return (
        f"the GL driver is {driver}; the NumPy backend copies llvmpipe of Mesa {EMULATED_MESA} "
        "bit for "
        "bit, so differences in hash-like or sign-of-zero pixels may be this driver's, not a bug"
    )


_MEASURED: dict[int, str | None] = {}


def driver_model(ctx) -> str | None:
    """The model the driver behind `ctx` follows (measured once per context), None if unknown."""
    key = id(ctx)
    if key not in _MEASURED:
        _MEASURED[key] = identify(measure(ctx))
    return _MEASURED[key]
