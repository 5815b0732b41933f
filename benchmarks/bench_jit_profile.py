"""Where one frame of the slowest real shaders spends its time, per runtime function.

    python benchmarks/bench_jit_profile.py [--only ID,...] [--size 128x72] [--top 14] [--jit
    on|off|auto]

Each shader (tools/real_verify.py's texts, fetched into tests/real_verify/texts) is compiled
for the NumPy backend, rendered once on one thread (warm-up: module execution, numba's load
with --jit on), then one more frame at a new iTime under cProfile. Printed per shader: its CPU
time, the functions with the most self time (a NumPy call made inside a Python function counts
as that function's self time, so `fadd` holds its additions); then over all shaders, each
function's share of its shader's self time summed (a ranking in which every shader weighs the
same). cProfile's overhead inflates functions made of many short calls; the ranking, not the
seconds, is the result. The default shaders are the slowest at 128x72 (docs/performance.md).
"""

from __future__ import annotations

import argparse
import collections
import cProfile
import os
import pstats
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tools"))

import real_verify  # noqa: E402
from bench_render import _load, frame_time  # noqa: E402

SLOW = "30-raymarch,36-raymarch,32-raytrace,52-2d,34-lighting,31-pathtrace,28-fbm,35-raymarch"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default=SLOW)
    ap.add_argument("--size", default="128x72")
    ap.add_argument("--top", type=int, default=14)
    ap.add_argument("--jit", default="on", choices=("on", "off", "auto"))
    args = ap.parse_args()
    os.environ["GLSLCHECK_JIT"] = args.jit
    from glslcheck.backends.numpy_engine.program import compile_numpy
    from glslcheck.shadertoy.sources import load_shader

    size = tuple(int(v) for v in args.size.split("x"))
    manifest = {e["id"]: e for e in real_verify.load_manifest()}
    share: collections.Counter = collections.Counter()
    calls: collections.Counter = collections.Counter()
    print(f"--jit {args.jit}, {size[0]}x{size[1]}, one thread; load {_load()}")
    for sid in args.only.split(","):
        path = real_verify.text_path(manifest[sid])
        if not path.exists():
            print(f"== {sid}: not fetched (python tools/real_verify.py fetch)")
            continue
        prog = compile_numpy(load_shader(str(path)))
        prog.parallel, prog.threads = "threads", 1
        prog.render(size=size, time=frame_time())
        prog._cache.clear()
        prof = cProfile.Profile()
        c0 = time.process_time()
        prof.enable()
        prog.render(size=size, time=frame_time())
        prof.disable()
        cpu = time.process_time() - c0
        stats = pstats.Stats(prof).stats
        total = sum(v[2] for v in stats.values()) or 1.0
        print(f"== {sid}: CPU {cpu:.2f} s under the profiler, self time {total:.2f} s")
        for (f, line, name), (_, n, tt, _, _) in sorted(stats.items(), key=lambda kv: -kv[1][2])[
            : args.top
        ]:
            print(
                f"   {tt:6.2f} s {100 * tt / total:5.1f}%  {n:8d} calls  "
                f"{os.path.basename(f)}:{line} {name}"
            )
        for (f, _, name), (_, n, tt, _, _) in stats.items():
            key = f"{os.path.basename(f)}:{name}"
            share[key] += tt / total
            calls[key] += n
    print("== summed share of each shader's self time")
    for key, v in share.most_common(30):
        print(f"   {v:5.2f}  {calls[key]:9d} calls  {key}")
    print(f"load at the end {_load()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
