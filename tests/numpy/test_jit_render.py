"""Frames with numba's compiled math kernels are the frames without them, bit for bit.

Every lab shader, the corpus shaders and a raymarcher written for this test (a march loop whose
lanes leave at different steps, calling sin, cos, tan, exp2, log2, pow and the built-ins made
from them, atan, atan(y, x), asin, acos and mix on the few lanes left, with edge arguments:
zeros, negative bases, huge angles, acos outside [-1, 1]) are
rendered with `--jit off` and `--jit on`, with and without FMA (runtime.HOST_FMA, which llvmpipe
follows), and the float32 frames compared bit for bit (NaN included). At 64x36 every call of
the emulation goes to a kernel (or is declined by it) on at most 2,304 lanes; 07_final also at
200x112, a whole tile of 22,400 lanes beside compacted regions. Skipped without numba on a
developer machine, a failure on CI (`jit_kernels`).
"""

from __future__ import annotations

import glob
import os

import numpy as np
import pytest

from glslcheck.backends.numpy_engine import runtime
from glslcheck.backends.numpy_engine.program import compile_numpy
from glslcheck.shadertoy.sources import load_shader

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHADERS = sorted(p for p in glob.glob(os.path.join(ROOT, "lab_shaders", "*")) if os.path.isdir(p))
SHADERS += sorted(glob.glob(os.path.join(ROOT, "tests", "corpus", "*.glsl")))

MARCH = """
float map(vec3 p) {
    vec3 q = p;
    q.xz = mat2(cos(iTime), sin(iTime), -sin(iTime), cos(iTime)) * q.xz;
    float d = length(q) - 1.0 - 0.1 * sin(7.0 * q.x + iTime) * cos(5.0 * q.y);
    return min(d, p.y + 1.2 + 0.05 * sin(3.0 * p.x) * sin(3.0 * p.z));
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 ro = vec3(0.0, 0.3, 3.0), rd = normalize(vec3(uv, -1.6));
    float t = 0.0, glow = 0.0;
    for (int i = 0; i < 64; i++) {
        float d = map(ro + rd * t);
        float a = atan(rd.y + d, rd.x - d) + atan(d * 4.0);
        glow += exp2(-8.0 * abs(d)) * 0.02 + 1e-3 * mix(a, asin(clamp(d, -1.0, 1.0)), fract(t * \
            3.0));
        if (d < 0.001 || t > 12.0) break;
        t += d;
    }
    vec3 p = ro + rd * t;
    float spec = pow(max(dot(normalize(p), normalize(vec3(1.0, 2.0, 1.5))), 0.0), 24.0 + uv.x * \
        8.0);
    float f = log2(1.0 + t) + tan(uv.x * 1.4) * 0.05;
    float edge = pow(uv.x, 0.5) + pow(0.0, uv.y + 1.0) + sin(uv.y * 3.0e9) + log(max(uv.x, 0.0));
    fragColor = vec4(spec + glow, f, exp(-0.3 * t) + 1e-3 * edge, acos(uv.y * 1.2));
}
"""


def _render(shader, mode: str, size: tuple[int, int], monkeypatch) -> np.ndarray:
    """One frame with --jit ``mode`` (read when the program's runtime makes its math functions,
    so each mode gets its own program), on threads: worker processes keep the mode they
    started with."""
    monkeypatch.setenv("GLSLCHECK_JIT", mode)
    prog = compile_numpy(shader)
    prog.parallel = "threads"
    with np.errstate(all="ignore"):
        return prog.render(size=size, time=1.7)


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and np.array_equal(a.view(np.int32), b.view(np.int32))


@pytest.mark.parametrize("fma", [True, False])
@pytest.mark.parametrize("path", SHADERS + ["march"], ids=lambda p: os.path.basename(p))
def test_frames_equal_with_and_without_kernels(jit_kernels, make_shader, monkeypatch, path, fma):
    monkeypatch.setattr(runtime, "HOST_FMA", fma)
    shader = make_shader(MARCH) if path == "march" else load_shader(path)
    sizes = [(64, 36)] + ([(200, 112)] if path.endswith("07_final") else [])
    for size in sizes:
        off = _render(shader, "off", size, monkeypatch)
        on = _render(shader, "on", size, monkeypatch)
        assert _same(off, on), (
            path,
            fma,
            size,
            int((off.view(np.int32) != on.view(np.int32)).sum()),
        )


def test_the_kernels_are_used(jit_kernels, make_shader, monkeypatch):
    """--jit on really takes the kernels (else the test above compares NumPy with itself): the
    raymarcher's frame makes hundreds of kernel calls."""
    from glslcheck.backends.numpy_engine import jit

    calls = []
    real = jit.compiled

    def counting(name, run, fma, kernels):
        fn = real(name, run, fma, kernels)

        def call(*args):
            calls.append(name)
            return fn(*args)

        return call

    monkeypatch.setattr(jit, "compiled", counting)
    _render(make_shader(MARCH), "on", (64, 36), monkeypatch)
    assert len(calls) > 100 and {
        "_sin",
        "_cos",
        "_exp2",
        "_pow",
        "_atan",
        "_atan2",
        "_asin",
        "_acos",
        "_mix",
    } <= set(calls), sorted(set(calls))


def test_workers_load_the_kernels_once_the_parent_decided(jit_kernels, make_shader, monkeypatch):
    """--parallel processes, auto: each worker reports the seconds of NumPy math it counted; the
    parent adds them up (jit.add_counted). Once the parent has decided (here: told so), the
    workers load the kernels before the next frame and count nothing more; the frames are the
    bits of --jit off either way."""
    from glslcheck.backends.numpy_engine import jit, workers
    from glslcheck.backends.numpy_engine import tiles as frame

    if not workers.available():
        if os.environ.get("CI"):
            pytest.fail(
                "worker processes are unavailable on the CI machine (Linux): "
                + str(workers._DISABLED)
            )
        pytest.skip("worker processes need Linux with memfd_create (this machine: threads only)")
    off = _render(make_shader(MARCH), "off", (64, 36), monkeypatch)
    monkeypatch.setenv("GLSLCHECK_JIT", "auto")
    monkeypatch.setattr(jit, "_STATE", state := jit._State())
    state.threshold = 1e9  # the parent decides only when told
    monkeypatch.setattr(frame, "TILE_LANES", 600)  # four tiles
    prog = compile_numpy(make_shader(MARCH))
    prog.parallel, prog.threads = "processes", 2
    try:
        with np.errstate(all="ignore"):
            first = prog.render(size=(64, 36), time=1.7)
            counted = state.workers_spent
            assert prog.last_parallel == "processes" and counted > 0 and not jit.decided()
            state.pays = True
            prog._cache.clear()
            second = prog.render(size=(64, 36), time=1.7)
        assert (
            prog.last_parallel == "processes" and state.workers_spent == counted
        )  # no NumPy math any more
        assert state.kernels is None  # the parent itself rendered nothing: it loaded nothing
    finally:
        workers.shutdown()
    assert _same(first, off) and _same(second, off)
