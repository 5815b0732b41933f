"""The default CPU program (`--backend auto`, backends/tiered.py) against the NumPy backend alone
and the compiled engine alone, as a user meets them.

    python benchmarks/bench_default.py [--repeat 5] [--frames 200] [--size 400x225]
                                       [--first LAB,...] [--steady PATH,...] [--during PATH,...]
                                       [--computed PATH,...]

1. First frame: a fresh process per run (`import glslcheck`, compile, one frame at 800x450,
   `render`'s default size), the default program and the NumPy backend in turns; the median
   and best wall time of `--repeat` runs each, and the default's median over the NumPy
   backend's (the goal: never above 1, up to the noise of a shared machine).
2. Steady state: in one process per engine, `--frames` frames of an animated scene (a new iTime
   each) at `--size`; the wall time of all of them (compile included), the median of the last
   tenth, and the mode the default program ended in; with GL, llvmpipe's median frame in the
   same process for the ratio. The engines run in turns, `--repeat` rounds; medians printed (a
   shared machine's load moves single runs by 2x). numba's cache is the user's: a first run on a
   machine compiles (the default moves after the frames have cost the compile's estimate), later
   runs load.
3. Frames during the compile (`--during`): one process per shader with a numba cache of its own
   (so numba compiles), frames at `--size` until the compiled engine renders or 120 s pass; the
   median NumPy frame before the compile starts against the median and the slowest NumPy frame
   while it runs (the compile's cost to the frames beside it), and the seconds until the first
   frame of the compiled engine.
4. Every frame computed (`--computed`): part 2 serves a scene that does not read iTime from
   the NumPy frame cache after its first frame; here the cache is emptied before every frame
   and NumPy runs on one thread, so that a frame's CPU time is the process's. One process per
   shader and engine (the default program and the NumPy backend alone), `--frames` frames at
   `--size`; the median CPU time of the last tenth against llvmpipe's median CPU time in the
   same process, the mean from the second frame on, where the default settled and from which
   frame it left NumPy.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

FIRST = "01_spheres_procedural,05_blinn_phong,07_final"
STEADY = (
    "benchmarks/scenes/lights_in_branch,lab_shaders/bonus_animated_lights,"
    "tests/real_verify/texts/29-raymarch.glsl"
)

FIRST_RUN = r"""
import json, sys, time
t0 = time.perf_counter()
import glslcheck
prog = glslcheck.compile(sys.argv[1], backend=sys.argv[2])
prog.render(size=(800, 450))
print(json.dumps({"seconds": time.perf_counter() - t0}))
"""

STEADY_RUN = r"""
import json, statistics, sys, time
t0 = time.perf_counter()
import glslcheck
path, backend, frames = sys.argv[1], sys.argv[2], int(sys.argv[3])
w, h = (int(x) for x in sys.argv[4].split("x"))
prog = glslcheck.compile(path, backend=backend)
times = []
for k in range(frames):
    t = time.perf_counter()
    prog.render(size=(w, h), time=1.0 + k / 60)
    times.append(time.perf_counter() - t)
total = time.perf_counter() - t0
tail = statistics.median(times[-max(1, frames // 10):])
gl = None
try:
    g = glslcheck.compile(path, backend="gl")
    g.render(size=(w, h))
    gt = []
    for k in range(10):
        t = time.perf_counter()
        g.render(size=(w, h), time=1.0 + k / 60)
        gt.append(time.perf_counter() - t)
    gl = statistics.median(gt)
except Exception:
    pass
print(json.dumps({"total": total, "tail": tail, "gl": gl,
                  "mode": getattr(prog.impl, "mode", backend)}))
"""


DURING_RUN = r"""
import atexit, json, os, shutil, statistics, sys, tempfile, time
os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="bench-default-")
atexit.register(shutil.rmtree, os.environ["NUMBA_CACHE_DIR"], True)
import glslcheck
path = sys.argv[1]
w, h = (int(x) for x in sys.argv[2].split("x"))
prog = glslcheck.compile(path)
impl = prog.impl
before, during, first, k = [], [], None, 0
t0 = time.perf_counter()
while time.perf_counter() - t0 < 120.0:
    mover = getattr(impl, "_mover", None)
    busy = mover is not None and mover.is_alive()
    t = time.perf_counter()
    prog.render(size=(w, h), time=1.0 + k / 60)
    took = time.perf_counter() - t
    k += 1
    if impl.mode != "numpy":
        first = time.perf_counter() - t0
        break
    if getattr(impl, "stay", None):
        break
    (during if busy else before if mover is None else []).append(took)
print(json.dumps({"before": statistics.median(before) if before else None,
                  "during": statistics.median(during) if during else None,
                  "slowest": max(during) if during else None, "n": len(during),
                  "first": first, "mode": impl.mode, "stay": getattr(impl, "stay", None)}))
"""

COMPUTED_RUN = r"""
import json, statistics, sys, time
import glslcheck
path, backend, frames = sys.argv[1], sys.argv[2], int(sys.argv[3])
w, h = (int(x) for x in sys.argv[4].split("x"))
prog = glslcheck.compile(path, backend=backend)
impl = prog.impl
numpy = getattr(impl, "first", impl)  # the tiered program's NumPy program, or NumPy itself
impl.threads = 1
cpu, modes = [], []
for k in range(frames):
    numpy._cache.clear()
    c = time.process_time()
    prog.render(size=(w, h), time=1.0 + k / 60)
    cpu.append(time.process_time() - c)
    modes.append(getattr(impl, "engine", "numpy"))
g = glslcheck.compile(path, backend="gl")
g.render(size=(w, h))
gl = []
for k in range(10):
    c = time.process_time()
    g.render(size=(w, h), time=1.0 + k / 60)
    gl.append(time.process_time() - c)
print(json.dumps({"tail": statistics.median(cpu[-max(1, frames // 10):]),
                  "mean": statistics.mean(cpu[1:] or cpu), "gl": statistics.median(gl),
                  "mode": modes[-1],
                  "left": next((i for i, m in enumerate(modes) if m != "numpy"), None)}))
"""


def computed(paths: list[str], frames: int, size: str) -> None:
    print(
        f"== every frame computed: {frames} frames at {size}, one process per engine, NumPy on "
        "one thread (CPU ms; ratio against llvmpipe's CPU time in the same process)"
    )
    for p in paths:
        path = p if os.path.isabs(p) else os.path.join(ROOT, p)
        row = []
        for backend in ("auto", "numpy"):
            r = _run(COMPUTED_RUN, path, backend, str(frames), size)
            left = f", left NumPy at frame {r['left']}" if r["left"] is not None else ""
            row.append(
                f"{backend} last frames {r['tail'] * 1000:6.1f} ms = {r['tail'] / r['gl']:.2f}x, "
                f"from the second {r['mean'] / r['gl']:.2f}x"
                + (f" ({r['mode']}{left})" if backend == "auto" else "")
            )
        print(f"{os.path.basename(path.rstrip('/'))}: " + " | ".join(row))


def during(paths: list[str], size: str) -> None:
    print(f"== NumPy frames beside a cold compile at {size} (wall ms; a numba cache of its own)")
    for p in paths:
        path = p if os.path.isabs(p) else os.path.join(ROOT, p)
        r = _run(DURING_RUN, path, size)
        ms = {
            k: (f"{r[k] * 1000:.0f}" if r[k] is not None else "-")
            for k in ("before", "during", "slowest")
        }
        first = f"{r['first']:.1f} s" if r["first"] is not None else f"never ({r['stay']})"
        print(
            f"{os.path.basename(path.rstrip('/'))}: before {ms['before']} | during median "
            f"{ms['during']}, slowest {ms['slowest']} ({r['n']} frames) | first compiled frame "
            f"after {first} ({r['mode']})"
        )


def _run(code: str, *args: str) -> dict:
    env = dict(os.environ, PYTHONPATH=ROOT)
    out = subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, env=env, check=True
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def first_frame(names: list[str], repeat: int) -> None:
    print(f"== first frame at 800x450, fresh process each, {repeat} runs in turns (wall seconds)")
    for name in names:
        path = os.path.join(ROOT, "lab_shaders", name)
        t: dict[str, list[float]] = {"auto": [], "numpy": []}
        for _ in range(repeat):
            for backend in t:
                t[backend].append(_run(FIRST_RUN, path, backend)["seconds"])
        med = {b: statistics.median(v) for b, v in t.items()}
        print(
            f"{name:24s} default median {med['auto']:.3f} best {min(t['auto']):.3f} | numpy "
            f"median {med['numpy']:.3f} best {min(t['numpy']):.3f} | default / numpy "
            f"{med['auto'] / med['numpy']:.2f}"
        )


def steady(paths: list[str], frames: int, size: str, repeat: int) -> None:
    print(
        f"== {frames} frames at {size}, one process per engine, {repeat} rounds in turns "
        "(medians; wall seconds)"
    )
    engines = ("auto", "numpy", "compiled")
    for p in paths:
        path = p if os.path.isabs(p) else os.path.join(ROOT, p)
        runs: dict[str, list[dict]] = {b: [] for b in engines}
        for _ in range(repeat):
            for backend in engines:
                runs[backend].append(_run(STEADY_RUN, path, backend, str(frames), size))
        row = []
        for backend in engines:
            total = statistics.median(r["total"] for r in runs[backend])
            tail = statistics.median(r["tail"] for r in runs[backend])
            gls = [r["gl"] for r in runs[backend] if r["gl"]]
            ratio = f" = {tail / statistics.median(gls):.2f}x gl" if gls else ""
            modes = ",".join(sorted({r["mode"] for r in runs[backend]}))
            row.append(
                f"{backend} {total:6.2f} s, last frames {tail * 1000:6.1f} ms{ratio}"
                + (f" ({modes})" if backend == "auto" else "")
            )
        print(f"{os.path.basename(path.rstrip('/'))}: " + " | ".join(row))


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--frames", type=int, default=100)
    p.add_argument("--size", default="400x225")
    p.add_argument("--first", default=FIRST, help="lab shaders for part 1, comma-separated, or all")
    p.add_argument("--steady", default=STEADY, help="shaders for part 2, comma-separated")
    p.add_argument("--during", default="", help="shaders for part 3, comma-separated")
    p.add_argument("--computed", default="", help="shaders for part 4, comma-separated")
    args = p.parse_args()
    if args.first:
        lab = os.path.join(ROOT, "lab_shaders")
        names = (
            sorted(d for d in os.listdir(lab) if os.path.isdir(os.path.join(lab, d)))
            if args.first == "all"
            else args.first.split(",")
        )
        first_frame(names, args.repeat)
    if args.steady:
        steady(args.steady.split(","), args.frames, args.size, args.repeat)
    if args.during:
        during(args.during.split(","), args.size)
    if args.computed:
        computed(args.computed.split(","), args.frames, args.size)
    return 0


if __name__ == "__main__":
    sys.exit(main())
