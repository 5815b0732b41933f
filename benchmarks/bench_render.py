"""Benchmark of the NumPy backend against the GL driver (moderngl on Mesa llvmpipe).

    python benchmarks/bench_render.py [--repeat N] [--skip-memory]

1. Speed: the scenes of `SCENES` at 800x450 (the four-sphere, four-point-light Blinn-Phong
   scene of benchmarks/scenes/four_spheres; the same scene with its lights built element by
   element in mainImage after background pixels have returned, benchmarks/scenes/lights_array;
   the same lights declared before and filled inside the branch the sphere pixels take,
   benchmarks/scenes/lights_in_branch;
   a scene in the shape of real Lab 4 submissions, benchmarks/scenes/lab4_submission, and the
   same with its lights array declared before and filled inside the branch the sphere pixels
   take, benchmarks/scenes/lab4_lights_in_branch; the lab's
   final scene, lab_shaders/07_final, if present), rendered by both backends in turns in the
   same run; best and median of N renders each (the NumPy frame cache is cleared before every
   render). Ratio = numpy / gl; the floor is 6x, the target 3x. NumPy is timed on worker
   processes (what long renders use, see glslcheck/backends/numpy_engine/workers.py) and on threads
   of this process; and as CPU time, NumPy on one thread against llvmpipe's CPU time over all its
   threads (the work each does: the least moved by other load on a shared machine).
   `--speed-only` runs this part alone, `--scene TEXT` only the scenes whose label holds TEXT.
2. Coverage scaling: the sphere scene with small spheres (10% of the pixels) and with large
   ones (99%; the share is counted from the render statistics: the lanes that ran the scene's
   hit branch). Background pixels should cost almost nothing (masked branches
   run only on the lanes that take them, and sparse ones are compacted): target
   time(small) / time(large) <= 35%. The two are rendered in turns, best of N each. The ratio
   of one-thread CPU times is printed too (wall times swing with other load on the machine,
   CPU times much less), and llvmpipe's ratio on the same scenes for reference.
3. Memory: peak resident memory of a 3840x2160 render in a fresh subprocess (ru_maxrss, and
   tracemalloc's peak of Python/NumPy allocations); must stay below 2 GB.
"""

from __future__ import annotations

import argparse
import itertools
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

from glslcheck.backends.numpy_engine.program import compile_numpy  # noqa: E402
from glslcheck.base.diagnostics import register_source  # noqa: E402
from glslcheck.shadertoy.sources import Shader, Source, load_shader  # noqa: E402

SCENE = os.path.join(HERE, "scenes", "four_spheres", "Image.glsl")
FINAL = os.path.join(ROOT, "lab_shaders", "07_final")
# The speed scenes: (label, shader folder). run_all.py renders the same list.
SCENES = [
    ("four spheres, four lights (Blinn-Phong)", os.path.dirname(SCENE)),
    ("lights array built in mainImage", os.path.join(HERE, "scenes", "lights_array")),
    ("lights array filled in a branch", os.path.join(HERE, "scenes", "lights_in_branch")),
    ("Lab 4 submission shape", os.path.join(HERE, "scenes", "lab4_submission")),
    (
        "Lab 4 shape, lights filled in a branch",
        os.path.join(HERE, "scenes", "lab4_lights_in_branch"),
    ),
    ("lab 07_final", FINAL),
]
SIZE = (800, 450)


def _best(fn, repeat: int, clock=time.perf_counter) -> float:
    """The shortest of ``repeat`` calls of ``fn`` by ``clock`` (wall time, or
    ``time.process_time`` for CPU time)."""
    best = float("inf")
    for _ in range(repeat):
        t0 = clock()
        fn()
        best = min(best, clock() - t0)
    return best


MODES = (
    "processes",
    "threads",
)  # NumpyProgram.parallel: worker processes, or threads of this process


_FRAMES = itertools.count()


def frame_time() -> float:
    """A new iTime for every NumPy frame, as an animation has: nothing computed from iTime can
    be reused from an earlier frame (the frame cache is emptied too; lane_memo.py keeps what
    depends on constants only)."""
    return next(_FRAMES) * 0.01


def _numpy_time(prog, repeat: int, size=SIZE, warm: bool = True, mode: str = "processes") -> float:
    def once():
        prog._cache.clear()
        prog.render(size=size, time=frame_time())

    prog.parallel = mode
    if warm:
        once()  # warm-up: module execution, workers or thread pool, caches
    t = _best(once, repeat)
    assert prog.last_parallel == mode, (prog.last_parallel, mode)  # measured what it says
    return t


def _numpy_cpu_time(prog, repeat: int, size=SIZE, warm: bool = True) -> float:
    """Best CPU time of a one-thread render: steadier than wall time on a shared machine."""
    threads = prog.threads
    prog.threads = 1
    try:
        prog._cache.clear()
        if warm:
            prog.render(size=size, time=frame_time())
        best = float("inf")
        for _ in range(repeat):
            prog._cache.clear()
            t0 = time.process_time()
            prog.render(size=size, time=frame_time())
            best = min(best, time.process_time() - t0)
        return best
    finally:
        prog.threads = threads


# Sphere radii of the coverage scenes: 10.3% and 99.2% of an 800x450 frame (printed by coverage()).
SMALL_RADIUS, LARGE_RADIUS = 0.7, 2.8


def _scene(radius: float) -> Shader:
    """The four-sphere scene with spheres of this radius (their centres stay)."""
    with open(SCENE, encoding="utf-8") as f:
        text = f.read()
    assert "#define SPHERE_RADIUS 0.85\n" in text
    text = text.replace("#define SPHERE_RADIUS 0.85\n", f"#define SPHERE_RADIUS {radius}\n")
    path = f"four_spheres_radius_{radius}.glsl"
    register_source(path, text)
    shader = Shader(root=path)
    shader.tabs["Image"] = Source(path, text, "Image")
    return shader


def sphere_coverage(prog) -> float:
    """The share of the pixels a ray of which hits a sphere: the lanes that ran the scene's
    `if (hit >= 0)` branch (render statistics), over all the pixels."""
    with open(SCENE, encoding="utf-8") as f:
        line = next(i for i, ln in enumerate(f, 1) if "if (hit >= 0)" in ln)
    prog = getattr(prog, "impl", prog)  # glslcheck.compile()'s Program wraps the NumPy program
    prog.render(size=SIZE, stats=True)
    lanes = [s.lanes for s in prog.last_stats if s.kind == "if" and s.line == line]
    assert len(lanes) == 1, prog.last_stats
    return lanes[0] / (SIZE[0] * SIZE[1])


def speed(repeat: int, only: str = "") -> None:
    import statistics

    from glslcheck.backends.gl import compile_gl, renderer_name

    print(
        f"== speed at {SIZE[0]}x{SIZE[1]} (best and median of {repeat}, in turns); GL: "
        f"{renderer_name()}; "
        f"NumPy on {os.cpu_count()} worker processes and on {os.cpu_count()} threads; "
        f"load {_load()} (1/5/15-minute load average)"
    )
    for name, folder in SCENES:
        if not os.path.isdir(folder) or only not in name:
            continue
        shader = load_shader(folder)
        prog = compile_numpy(shader)
        gl = compile_gl(shader)
        gl.render(size=SIZE)
        for mode in MODES:
            _numpy_time(prog, 1, mode=mode)  # warm-up
        t: dict[str, list[float]] = {m: [] for m in MODES + ("gl", "cpu", "gl cpu")}
        for _ in range(repeat):  # in turns, so a slow spell of a shared machine hits all
            for mode in MODES:
                t[mode].append(_numpy_time(prog, 1, warm=False, mode=mode))
            t["gl"].append(_best(lambda: gl.render(size=SIZE), 1))
            t["cpu"].append(_numpy_cpu_time(prog, 1, warm=False))
            c0 = time.process_time()  # llvmpipe's threads are this process's: all of its CPU time
            gl.render(size=SIZE)
            t["gl cpu"].append(time.process_time() - c0)
        for how, pick in (("best", min), ("median", statistics.median)):
            v = {k: pick(x) for k, x in t.items()}
            print(
                f"{name:40s} {how:6s} gl {v['gl'] * 1000:6.1f} ms   numpy processes "
                f"{v['processes'] * 1000:6.1f} ms "
                f"= {v['processes'] / v['gl']:5.2f}x   threads {v['threads'] * 1000:6.1f} ms "
                f"= {v['threads'] / v['gl']:5.2f}x   CPU: numpy one thread "
                f"{v['cpu'] * 1000:6.1f} ms, "
                f"gl {v['gl cpu'] * 1000:6.1f} ms = {v['cpu'] / v['gl cpu']:5.2f}x"
            )
    print(f"(floor 6x, target 3x); load at the end {_load()}")


def _load() -> str:
    return " ".join(f"{x:.1f}" for x in os.getloadavg())


def coverage(repeat: int) -> None:
    """Small and large spheres rendered in turns (so a slow spell of a shared machine hits both),
    best of `repeat` rounds each: wall time on worker processes and on threads, and one-thread
    CPU time. llvmpipe's own ratio on the same two scenes is printed for reference."""
    from glslcheck.backends.gl import compile_gl

    print("== coverage scaling (four-sphere scene)")
    progs, gls, cov = {}, {}, {}
    for label, radius in (("small", SMALL_RADIUS), ("large", LARGE_RADIUS)):
        shader = _scene(radius)
        progs[label] = prog = compile_numpy(shader)
        cov[label] = sphere_coverage(prog)
        gls[label] = compile_gl(shader)
        gls[label].render(size=SIZE)
        for mode in MODES:
            _numpy_time(prog, 1, mode=mode)
    keys = MODES + ("cpu", "gl")
    t = {(label, k): float("inf") for label in progs for k in keys}
    for _ in range(repeat):
        for label, prog in progs.items():
            for mode in MODES:
                t[label, mode] = min(t[label, mode], _numpy_time(prog, 1, warm=False, mode=mode))
            t[label, "cpu"] = min(t[label, "cpu"], _numpy_cpu_time(prog, 1, warm=False))
            t[label, "gl"] = min(t[label, "gl"], _best(lambda: gls[label].render(size=SIZE), 1))
    for label in progs:
        print(
            f"{label:6s} spheres cover {cov[label] * 100:5.1f}% of the pixels: processes "
            f"{t[label, 'processes'] * 1000:5.1f} ms, threads {t[label, 'threads'] * 1000:5.1f} "
            "ms, "
            f"one thread {t[label, 'cpu'] * 1000:5.1f} ms CPU; gl {t[label, 'gl'] * 1000:5.1f} ms"
        )
    r = {k: t["small", k] / t["large", k] for k in keys}
    print(
        f"time(small) / time(large) on processes = {r['processes']:.1%} (target <= 35%); "
        f"threads {r['threads']:.0%}; one-thread CPU {r['cpu']:.0%}; "
        f"llvmpipe for reference {r['gl']:.0%}"
    )


_MEMORY_CHILD = """
import resource, sys, time, tracemalloc
sys.path.insert(0, {root!r})
from glslcheck.shadertoy.sources import load_shader
from glslcheck.backends.numpy_engine import workers
from glslcheck.backends.numpy_engine.program import compile_numpy
prog = compile_numpy(load_shader({scene!r}))
prog.parallel = {mode!r}
if {mode!r} == "processes":
    prog.render(size=(512, 512))  # start the workers first: the time below is the render's
tracemalloc.start()
t0 = time.perf_counter()
img = prog.render(size=(3840, 2160))
t1 = time.perf_counter()
assert prog.last_parallel in ({mode!r}, "one thread")
_, peak = tracemalloc.get_traced_memory()
workers.shutdown()  # waited for: their peak shows in RUSAGE_CHILDREN
kids = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024
print(img.shape, round(t1 - t0, 2), peak, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * \
    1024, kids)
"""


def memory() -> None:
    """Peak resident memory of a 3840x2160 render: the process itself, and with worker processes
    the largest worker times their number on top (an upper bound on their sum)."""
    print("== memory of a 3840x2160 render (fresh process)")
    for mode in ("threads", "processes"):
        out = subprocess.run(
            [sys.executable, "-c", _MEMORY_CHILD.format(root=ROOT, scene=SCENE, mode=mode)],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.split()
        seconds, traced, rss, kids = float(out[-4]), int(out[-3]), int(out[-2]), int(out[-1])
        total = rss + (kids * (os.cpu_count() or 1) if mode == "processes" else 0)
        extra = (
            f" + workers {os.cpu_count()} x {kids / 2**20:.0f} MiB" if mode == "processes" else ""
        )
        print(
            f"{mode:9s}: render {seconds:.2f} s; tracemalloc peak {traced / 2**20:.0f} MiB; "
            f"peak resident {rss / 2**20:.0f} MiB{extra} = {total / 2**20:.0f} MiB (limit 2048 MiB)"
        )


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeat", type=int, default=9)
    p.add_argument("--skip-memory", action="store_true")
    p.add_argument("--speed-only", action="store_true", help="part 1 only")
    p.add_argument("--scene", default="", help="part 1 on the scenes whose label holds this")
    args = p.parse_args()
    speed(args.repeat, args.scene)
    if args.speed_only:
        return 0
    coverage(args.repeat)
    if not args.skip_memory:
        memory()
    return 0


if __name__ == "__main__":
    sys.exit(main())
