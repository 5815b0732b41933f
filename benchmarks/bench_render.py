"""Benchmark of the NumPy backend against the GL driver (moderngl on Mesa llvmpipe).

    python benchmarks/bench_render.py [--repeat N] [--skip-memory]

1. Speed: the four-sphere, four-point-light Blinn-Phong scene (benchmarks/scenes/four_spheres)
   and the lab's final scene (lab_shaders/07_final, if present) at 800x450, rendered by both
   backends in turns in the same run; best of N renders each (the NumPy frame cache is cleared
   before every render). Ratio = numpy / gl; the floor is 6x, the target 3x.
2. Coverage scaling: the sphere scene with small spheres (~10% of the pixels) and with large
   ones (nearly all pixels). Background pixels should cost almost nothing (masked branches
   run only on the lanes that take them, and sparse ones are compacted): target
   time(small) / time(large) <= 35%. The two are rendered in turns, best of N each. The ratio
   of one-thread CPU times is printed too (wall times swing with other load on the machine,
   CPU times much less), and llvmpipe's ratio on the same scenes for reference.
3. Memory: peak resident memory of a 3840x2160 render in a fresh subprocess (ru_maxrss, and
   tracemalloc's peak of Python/NumPy allocations); must stay below 2 GB.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

from glslcheck.sources import Shader, Source, load_shader  # noqa: E402
from glslcheck.diagnostics import register_source  # noqa: E402
from glslcheck.numpy_backend.program import compile_numpy  # noqa: E402

SCENE = os.path.join(HERE, "scenes", "four_spheres", "Image.glsl")
FINAL = os.path.join(ROOT, "lab_shaders", "07_final")
SIZE = (800, 450)


def _best(fn, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def _numpy_time(prog, repeat: int, size=SIZE, warm: bool = True) -> float:
    def once():
        prog._cache.clear()
        prog.render(size=size)

    if warm:
        once()  # warm-up: module execution, thread pool, caches
    return _best(once, repeat)


def _numpy_cpu_time(prog, repeat: int, size=SIZE, warm: bool = True) -> float:
    """Best CPU time of a one-thread render: steadier than wall time on a shared machine."""
    threads = prog.threads
    prog.threads = 1
    try:
        prog._cache.clear()
        if warm:
            prog.render(size=size)
        best = float("inf")
        for _ in range(repeat):
            prog._cache.clear()
            t0 = time.process_time()
            prog.render(size=size)
            best = min(best, time.process_time() - t0)
        return best
    finally:
        prog.threads = threads


def _scene(scale: float) -> Shader:
    with open(SCENE, encoding="utf-8") as f:
        text = f.read().replace("#define SPHERE_SCALE 1.0", f"#define SPHERE_SCALE {scale}")
    path = f"four_spheres_scale_{scale}.glsl"
    register_source(path, text)
    shader = Shader(root=path)
    shader.tabs["Image"] = Source(path, text, "Image")
    return shader


def speed(repeat: int) -> None:
    from glslcheck.gl_backend import compile_gl, renderer_name

    print(f"== speed at {SIZE[0]}x{SIZE[1]} (best of {repeat}); GL: {renderer_name()}")
    scenes = [("four spheres, four lights (Blinn-Phong)", load_shader(SCENE))]
    if os.path.isdir(FINAL):
        scenes.append(("lab 07_final", load_shader(FINAL)))
    for name, shader in scenes:
        prog = compile_numpy(shader)
        gl = compile_gl(shader)
        gl.render(size=SIZE)
        _numpy_time(prog, 1)  # warm-up
        t_np = t_gl = float("inf")
        for _ in range(repeat):  # in turns, so a slow spell of a shared machine hits both
            t_np = min(t_np, _numpy_time(prog, 1, warm=False))
            t_gl = min(t_gl, _best(lambda: gl.render(size=SIZE), 1))
        print(f"{name:42s} numpy {t_np * 1000:8.1f} ms   gl {t_gl * 1000:8.1f} ms   ratio {t_np / t_gl:5.2f}x "
              f"(floor 6x, target 3x)")


def coverage(repeat: int) -> None:
    """Small and large spheres rendered in turns (so a slow spell of a shared machine hits both),
    best of `repeat` rounds each: wall time with the default threads, and one-thread CPU time.
    llvmpipe's own ratio on the same two scenes is printed for reference."""
    from glslcheck.gl_backend import compile_gl

    print("== coverage scaling (four-sphere scene)")
    progs, gls, cov = {}, {}, {}
    for label, scale in (("small", 0.85), ("large", 2.6)):
        shader = _scene(scale)
        progs[label] = prog = compile_numpy(shader)
        img = prog.render(size=SIZE)
        background = np.all(np.abs(img[..., :3] - img[0, 0, :3]) < 1e-6, axis=-1)
        cov[label] = 1.0 - background.mean()
        gls[label] = compile_gl(shader)
        gls[label].render(size=SIZE)
        _numpy_time(prog, 1)
    wall = {k: float("inf") for k in progs}
    cpu = dict(wall)
    gl = dict(wall)
    for _ in range(repeat):
        for label, prog in progs.items():
            wall[label] = min(wall[label], _numpy_time(prog, 1, warm=False))
            cpu[label] = min(cpu[label], _numpy_cpu_time(prog, 1, warm=False))
            gl[label] = min(gl[label], _best(lambda: gls[label].render(size=SIZE), 1))
    for label in progs:
        print(f"{label:6s} spheres cover {cov[label] * 100:5.1f}% of the pixels: {wall[label] * 1000:8.1f} ms"
              f"   (one thread: {cpu[label] * 1000:6.1f} ms CPU; gl {gl[label] * 1000:5.1f} ms)")
    print(f"time(small) / time(large) = {wall['small'] / wall['large'] * 100:.0f}% (target <= 35%); "
          f"one-thread CPU time: {cpu['small'] / cpu['large'] * 100:.0f}%; "
          f"llvmpipe for reference: {gl['small'] / gl['large'] * 100:.0f}%")


_MEMORY_CHILD = """
import resource, sys, time, tracemalloc
sys.path.insert(0, {root!r})
from glslcheck.sources import load_shader
from glslcheck.numpy_backend.program import compile_numpy
prog = compile_numpy(load_shader({scene!r}))
tracemalloc.start()
t0 = time.perf_counter()
img = prog.render(size=(3840, 2160))
t1 = time.perf_counter()
_, peak = tracemalloc.get_traced_memory()
print(img.shape, round(t1 - t0, 2), peak, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)
"""


def memory() -> None:
    print("== memory of a 3840x2160 render (fresh process)")
    out = subprocess.run([sys.executable, "-c", _MEMORY_CHILD.format(root=ROOT, scene=SCENE)],
                         capture_output=True, text=True, check=True).stdout.split()
    seconds, traced, rss = float(out[-3]), int(out[-2]), int(out[-1])
    print(f"render {seconds:.2f} s; tracemalloc peak {traced / 2**20:.0f} MiB; "
          f"peak resident {rss / 2**20:.0f} MiB (limit 2048 MiB)")


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeat", type=int, default=9)
    p.add_argument("--skip-memory", action="store_true")
    args = p.parse_args()
    speed(args.repeat)
    coverage(args.repeat)
    if not args.skip_memory:
        memory()
    return 0


if __name__ == "__main__":
    sys.exit(main())
