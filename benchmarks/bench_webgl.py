"""Benchmark of the WebGL backend (headless Chromium, ANGLE on SwiftShader) against GL (Mesa
llvmpipe).

    python benchmarks/bench_webgl.py [--runs N] [--starts N]

1. Browser start-up: a new Browser (Playwright's driver, Chromium, the page, the WebGL2 context
   and harness) is started and closed `--starts` times; the unit it is given in is one GL render
   of 07_final at 800x450 timed in the same run ("start-up = N GL frames"): the number of frames
   a render must save before the browser pays for itself.
2. Render time per frame, WebGL against GL, the same shader and inputs, rendered in turns
   (median of `--runs` after a warm-up render each): lab 07_final and 01_spheres_procedural at
   160x90, 320x180 and 800x450. A WebGL frame is the whole `WebGLProgram.render` call: uniforms,
   draw, readPixels(FLOAT), base64 through the DevTools pipe, decode; a GL frame is
   `GLProgram.render` (uniforms, draw, read-back). Ratio = webgl / gl.
3. Where a WebGL frame's time goes: a 1x1 render of the same program (the round trip through
   Playwright and the page, nothing to draw or move) and a 800x450 readback of an empty
   shader (the transfer of 5.8 MB of floats), each against the full frame.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

from glslcheck.backends.gl import compile_gl, renderer_name  # noqa: E402
from glslcheck.backends.webgl import Browser, close_browser, compile_webgl, get_browser  # noqa: E402
from glslcheck.base.diagnostics import register_source  # noqa: E402
from glslcheck.shadertoy.sources import Shader, Source, load_shader  # noqa: E402

SHADERS = ("07_final", "01_spheres_procedural")
SIZES = ((160, 90), (320, 180), (800, 450))


def _timed(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def _in_turns(fns: dict, runs: int) -> dict[str, float]:
    """Median seconds of each function, one warm-up each, then `runs` rounds in turns."""
    for fn in fns.values():
        fn()
    times: dict[str, list[float]] = {k: [] for k in fns}
    for _ in range(runs):
        for k, fn in fns.items():
            times[k].append(_timed(fn))
    return {k: statistics.median(v) for k, v in times.items()}


def _empty_shader() -> Shader:
    text = "void mainImage(out vec4 c, in vec2 f) { c = vec4(0.0); }\n"
    register_source("Empty.glsl", text)
    shader = Shader(root="<empty>")
    shader.tabs["Image"] = Source("Empty.glsl", text, "Image")
    return shader


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=7)
    p.add_argument("--starts", type=int, default=3)
    args = p.parse_args()
    print(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} at start")
    close_browser()

    final = load_shader(os.path.join(ROOT, "lab_shaders", "07_final"))
    gl_final = compile_gl(final)
    print(f"GL: {renderer_name()}")
    one_gl = _in_turns({"gl": lambda: gl_final.render(size=(800, 450))}, args.runs)["gl"]
    starts = []
    for _ in range(args.starts):
        t0 = time.perf_counter()
        b = Browser()
        starts.append(time.perf_counter() - t0)
        info = b.info
        b.close()
    start = statistics.median(starts)
    print(f"WebGL: {info['renderer']}")
    print(
        "\n1. browser start-up (Playwright driver + Chromium + page + WebGL2 context), "
        f"median of {args.starts}: {start * 1000:.0f} ms = {start / one_gl:.0f} GL frames of "
        "07_final at 800x450 "
        f"({one_gl * 1000:.1f} ms each, same run); starts: "
        f"{', '.join(f'{s * 1000:.0f}' for s in starts)} ms"
    )

    get_browser()
    print(f"\n2. render time per frame, median of {args.runs} in turns (ms); ratio = webgl / gl")
    print(f"   {'shader':<24}{'size':>9}{'gl':>9}{'webgl':>9}{'ratio':>8}")
    rows = []
    for name in SHADERS:
        shader = load_shader(os.path.join(ROOT, "lab_shaders", name))
        gl, webgl = compile_gl(shader), compile_webgl(shader)
        for size in SIZES:
            t = _in_turns(
                {"gl": lambda: gl.render(size=size), "webgl": lambda: webgl.render(size=size)},
                args.runs,
            )
            rows.append((name, size, t["gl"], t["webgl"]))
            print(
                f"   {name:<24}{size[0]:>5}x{size[1]:<3}"
                f"{t['gl'] * 1000:>9.1f}{t['webgl'] * 1000:>9.1f}"
                f"{t['webgl'] / t['gl']:>8.1f}"
            )

    webgl_final, empty = compile_webgl(final), compile_webgl(_empty_shader())
    t = _in_turns(
        {
            "frame": lambda: webgl_final.render(size=(800, 450)),
            "tiny": lambda: webgl_final.render(size=(1, 1)),
            "empty": lambda: empty.render(size=(800, 450)),
        },
        args.runs,
    )
    print(
        f"\n3. a WebGL frame of 07_final at 800x450: {t['frame'] * 1000:.1f} ms; of it, "
        "the round trip "
        f"(1x1 render) {t['tiny'] * 1000:.1f} ms = {t['tiny'] / t['frame']:.0%}, an empty shader's "
        f"800x450 frame (clear, draw, read back, transfer) {t['empty'] * 1000:.1f} ms = "
        f"{t['empty'] / t['frame']:.0%}"
    )
    print(f"\nload average {os.getloadavg()[0]:.2f} at the end")
    close_browser()
    return 0


if __name__ == "__main__":
    sys.exit(main())
