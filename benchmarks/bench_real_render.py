"""NumPy render time against GL (llvmpipe) on the real public shaders of tools/real_verify.py.

    python tools/real_verify.py fetch [--mirror DIR]      # the texts, into tests/real_verify/texts
    python benchmarks/bench_real_render.py [--size 400x225] [--repeat 3] [--only ID,...]
                                           [--mode threads|processes|one] [--json out.json]
                                           [--set main|holdout]

Every shader that both backends render is timed in this one process, the two backends in turns,
best of `--repeat` frames each, every frame at a new iTime (0.01 apart, as an animation: the
NumPy frame cache is emptied and nothing computed from iTime is reused). Ratio = numpy / gl. It
prints one line per shader, slowest ratio first, then the geometric mean (the targets: <= 1.5x, and
no shader over 6x) and the load average at the start and the end (a shared machine moves both sides
of a ratio alike, single timings much more). Each frame's CPU time is measured too (this
process's: llvmpipe's threads are in it) and its ratio printed beside: the least disturbed by
other load, and with `--mode one` the work NumPy does against the work llvmpipe does. Shaders
that a backend refuses are listed, not timed.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tools"))

import real_verify  # noqa: E402
from bench_render import _best, _load, frame_time  # noqa: E402

from glslcheck.base.diagnostics import GlslError  # noqa: E402
from glslcheck.shadertoy.sources import load_shader  # noqa: E402


def measure(path: str, size: tuple[int, int], repeat: int, mode: str) -> dict:
    from glslcheck.backends.gl import compile_gl
    from glslcheck.backends.numpy_engine.program import compile_numpy

    shader = load_shader(path)
    prog = compile_numpy(shader)
    if mode == "one":
        prog.parallel, prog.threads = "threads", 1
    else:
        prog.parallel = mode
    gl = compile_gl(shader)

    def numpy_frame():
        prog._cache.clear()
        prog.render(size=size, time=frame_time())

    def gl_frame():
        gl.render(size=size, time=frame_time())

    numpy_frame()  # warm-up: module execution, thread pool or workers
    gl_frame()
    t = {
        "numpy": float("inf"),
        "gl": float("inf"),
        "numpy cpu": float("inf"),
        "gl cpu": float("inf"),
    }
    for _ in range(repeat):  # in turns
        for name, fn in (("numpy", numpy_frame), ("gl", gl_frame)):
            c0 = time.process_time()  # this process's CPU time: llvmpipe's threads included
            t[name] = min(t[name], _best(fn, 1))
            t[name + " cpu"] = min(t[name + " cpu"], time.process_time() - c0)
    return dict(t, ratio=t["numpy"] / t["gl"], cpu_ratio=t["numpy cpu"] / t["gl cpu"])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", default="400x225")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", default="", help="comma-separated manifest ids")
    ap.add_argument(
        "--mode",
        default="threads",
        choices=("threads", "processes", "one"),
        help="NumPy on threads of this process (what a one-frame render uses), worker processes, "
        "or one thread",
    )
    ap.add_argument("--json", help="write the per-shader figures here")
    ap.add_argument(
        "--set",
        choices=tuple(real_verify.SETS),
        help="tools/real_verify.py's corpus: main (tuned on; the default, "
        "or REAL_VERIFY_SET) or holdout",
    )
    args = ap.parse_args()
    if args.set:
        real_verify.select(args.set)
    size = tuple(int(v) for v in args.size.split("x"))
    only = {s for s in args.only.split(",") if s}
    entries = [e for e in real_verify.load_manifest() if not only or e["id"] in only]
    print(
        f"corpus {os.environ['REAL_VERIFY_SET']}: NumPy ({args.mode}) against GL at "
        f"{size[0]}x{size[1]}, best of {args.repeat}; "
        f"load {_load()} (1/5/15-minute load average)",
        flush=True,
    )
    results, skipped = {}, {}
    for e in entries:
        path = real_verify.text_path(e)
        if not path.exists():
            skipped[e["id"]] = "not fetched"
            continue
        try:
            results[e["id"]] = r = dict(
                measure(str(path), size, args.repeat, args.mode), kind=e.get("kind", "")
            )
            print(
                f"  ({e['id']}: {r['ratio']:.2f}x, CPU {r['cpu_ratio']:.2f}x, load {_load()})",
                flush=True,
            )
        except GlslError as err:
            skipped[e["id"]] = str(err).splitlines()[0][:100]
        except Exception as err:  # a shader the GL driver rejects, ...
            skipped[e["id"]] = (
                f"{type(err).__name__}: {str(err).splitlines()[0][:100] if str(err) else ''}"
            )
    for sid, r in sorted(results.items(), key=lambda kv: -kv[1]["ratio"]):
        print(
            f"  {sid:22s} {r['kind']:16s} numpy {r['numpy'] * 1000:8.1f} ms  gl "
            f"{r['gl'] * 1000:7.1f} ms  "
            f"{r['ratio']:6.2f}x   CPU numpy {r['numpy cpu'] * 1000:8.1f} ms  gl "
            f"{r['gl cpu'] * 1000:7.1f} ms  "
            f"{r['cpu_ratio']:6.2f}x",
            flush=True,
        )
    for sid, why in skipped.items():
        print(f"  {sid:22s} not timed: {why}")
    for key, what in (("ratio", "wall time"), ("cpu_ratio", "CPU time")):
        if not results:
            break
        geo = math.exp(sum(math.log(r[key]) for r in results.values()) / len(results))
        worst = max(results.items(), key=lambda kv: kv[1][key])
        print(
            f"{what}: {len(results)} shaders, geometric mean {geo:.2f}x (target 1.5x); "
            f"worst {worst[0]} "
            f"{worst[1][key]:.1f}x (target 6x); over 6x: "
            f"{sum(r[key] > 6 for r in results.values())}"
        )
    print(f"load at the end {_load()}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"size": size, "results": results, "skipped": skipped}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
