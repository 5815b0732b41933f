"""What emulating llvmpipe's math costs the NumPy backend (ratios measured in one process).

    python benchmarks/bench_llvmpipe_math.py [--repeat N]

1. Per built-in: `Runtime("float32")` (llvmpipe's sin/cos/exp2/log2/pow step by step, with a
   correctly rounded fused multiply-add on an FMA CPU) against NumPy's own float32 ufunc on the
   same 1,000,000 arguments, then on one render tile's worth (TILE_LANES, 49,152: the size a
   frame's built-in calls have); best of N each, in turns. Ratio = emulated / NumPy.
2. Whole frames at 800x450: the four-sphere scene (benchmarks/scenes/four_spheres) and a value
   noise shader (a sin hash, 5 octaves), rendered with the emulation and with the runtime's
   transcendental functions swapped back to NumPy's (`rt.lp = None`) and Mesa's constant
   folding off (`rt.fold_constants = False`); best of N each, frame cache cleared. Ratio =
   emulated / plain. No target: the emulation buys bit-exact agreement with llvmpipe (the
   verify tests), and this says what it costs.
3. ``--against REV``: this tree's LlvmpipeMath against the one in git revision REV (its
   runtime.py loaded as a second module), on the lane counts a call has after compaction (300)
   and on one tile (TILE_LANES); both on the same arguments, in turns, CPU time (user+sys,
   best of N rounds); the results must agree bit for bit. Ratio = this tree / REV.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

from glslcheck.backends.numpy_engine.llvmpipe_reference import HOST_FMA  # noqa: E402
from glslcheck.backends.numpy_engine.program import compile_numpy  # noqa: E402
from glslcheck.backends.numpy_engine.runtime import Runtime  # noqa: E402
from glslcheck.backends.numpy_engine.tiles import TILE_LANES  # noqa: E402
from glslcheck.base.diagnostics import register_source  # noqa: E402
from glslcheck.shadertoy.sources import Shader, Source, load_shader  # noqa: E402

NOISE = """
float hash(vec2 p) { return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453); }
float noise(vec2 p) {
    vec2 i = floor(p), f = fract(p);
    vec2 u = f * f * (3.0 - 2.0 * f);
    return mix(mix(hash(i), hash(i + vec2(1.0, 0.0)), u.x),
               mix(hash(i + vec2(0.0, 1.0)), hash(i + vec2(1.0, 1.0)), u.x), u.y);
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = fragCoord / iResolution.y * 8.0 + iTime;
    float v = 0.0, a = 0.5;
    for (int o = 0; o < 5; o++) { v += a * noise(p); p *= 2.0; a *= 0.5; }
    fragColor = vec4(vec3(pow(v, 1.5), exp(-v), log(1.0 + v)), 1.0);
}
"""


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def builtins(repeat: int) -> None:
    rt = Runtime("float32")
    rng = np.random.default_rng(0)
    for lanes, calls in ((1_000_000, 1), (TILE_LANES, 20)):
        x = rng.uniform(-100, 100, lanes).astype(np.float32)
        pos = np.abs(x) + np.float32(1e-3)
        y = rng.uniform(-4, 4, x.size).astype(np.float32)
        cases = [
            ("sin", lambda: rt.sin(x), lambda: np.sin(x)),
            ("cos", lambda: rt.cos(x), lambda: np.cos(x)),
            ("tan", lambda: rt.tan(x), lambda: np.tan(x)),
            ("exp2", lambda: rt.exp2(y), lambda: np.exp2(y)),
            ("log2", lambda: rt.log2(pos), lambda: np.log2(pos)),
            ("pow", lambda: rt.pow(pos, y), lambda: np.exp2(y * np.log2(pos))),
        ]
        print(
            f"1. built-ins on {lanes:,} float32 arguments (FMA CPU: {HOST_FMA}), {calls} call(s), "
            f"best of {repeat}"
        )
        with rt.errstate():
            for name, ours, numpy in cases:
                a = best(lambda: [ours() for _ in range(calls)], repeat) / calls
                b = best(lambda: [numpy() for _ in range(calls)], repeat) / calls
                print(
                    f"   {name:<5} emulated {a * 1e3:7.2f} ms   numpy {b * 1e3:6.2f} ms   ratio "
                    f"{a / b:5.1f}x"
                )


def frames(repeat: int) -> None:
    register_source("noise/Image.glsl", NOISE)
    scenes = [
        ("four spheres", load_shader(os.path.join(HERE, "scenes", "four_spheres", "Image.glsl"))),
        ("value noise", Shader({"Image": Source("noise/Image.glsl", NOISE)}, "noise")),
    ]
    print(f"2. frames at 800x450, best of {repeat} (emulated vs NumPy math, folding off)")
    for name, shader in scenes:
        prog = compile_numpy(shader)
        prog.parallel = "threads"
        rt = prog.module("float32")["rt"]
        lp, fold = rt.lp, rt.fold_constants

        def render():
            prog._cache.clear()
            prog.render(size=(800, 450), time=1.0)

        timings = {}
        for mode in ("emulated", "plain"):
            rt.lp, rt.fold_constants = (lp, fold) if mode == "emulated" else (None, False)
            timings[mode] = best(render, repeat)
        rt.lp, rt.fold_constants = lp, fold
        print(
            f"   {name:<13} emulated {timings['emulated']:6.3f} s   plain "
            f"{timings['plain']:6.3f} s   "
            f"ratio {timings['emulated'] / timings['plain']:4.2f}x"
        )


def runtime_at(rev: str):
    """glslcheck/backends/numpy_engine/runtime.py as of git revision ``rev``, imported as a sibling
    module of the package (its relative imports resolve to this tree's modules)."""
    text = subprocess.run(
        ["git", "-C", ROOT, "show", f"{rev}:glslcheck/backends/numpy_engine/runtime.py"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    name = "glslcheck.backends.numpy_engine._runtime_at_rev"
    spec = importlib.util.spec_from_loader(name, loader=None)
    mod = importlib.util.module_from_spec(spec)
    mod.__package__ = "glslcheck.backends.numpy_engine"
    sys.modules[name] = mod
    exec(compile(text, f"{rev}:runtime.py", "exec"), mod.__dict__)
    return mod


def against(rev: str, repeat: int) -> None:
    old_lp, new_lp = runtime_at(rev).LlvmpipeMath(), Runtime("float32").lp
    rng = np.random.default_rng(1)
    print(
        f"3. LlvmpipeMath of this tree vs {rev}, CPU time per call, best of {repeat} rounds "
        f"(FMA CPU: {HOST_FMA}; load average {' '.join(f'{v:.1f}' for v in os.getloadavg())})"
    )
    for lanes, calls in ((300, 400), (TILE_LANES, 4)):
        x = rng.uniform(-100, 100, lanes).astype(np.float32)
        pos = np.abs(x) + np.float32(1e-3)
        y = rng.uniform(-4, 4, lanes).astype(np.float32)
        cases = [
            ("sin", lambda lp: lp.sin_or_cos(x, cos=False)),
            ("cos", lambda lp: lp.sin_or_cos(x, cos=True)),
            ("exp2", lambda lp: lp.exp2(y)),
            ("log2", lambda lp: lp.log2(pos)),
            ("pow", lambda lp: lp.pow(pos, y)),
        ]
        with np.errstate(all="ignore"):
            for name, fn in cases:
                assert np.array_equal(fn(new_lp).view(np.int32), fn(old_lp).view(np.int32)), name
                t = {"old": [], "new": []}
                for _ in range(repeat):
                    for key, lp in (("old", old_lp), ("new", new_lp)):
                        c = time.process_time()
                        for _ in range(calls):
                            fn(lp)
                        t[key].append((time.process_time() - c) / calls)
                a, b = min(t["new"]), min(t["old"])
                print(
                    f"   {lanes:>6,} lanes {name:<5} this {a * 1e6:8.1f} us   {rev} "
                    f"{b * 1e6:8.1f} us   "
                    f"ratio {a / b:4.2f}"
                )


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument(
        "--against", metavar="REV", help="compare LlvmpipeMath with git revision REV only"
    )
    args = p.parse_args()
    if args.against:
        against(args.against, args.repeat)
        return
    builtins(args.repeat)
    frames(max(1, args.repeat // 2))


if __name__ == "__main__":
    main()
