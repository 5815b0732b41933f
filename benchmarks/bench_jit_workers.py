"""The compiled math kernels in render worker processes once the parent has chosen them.

    python benchmarks/bench_jit_workers.py SHADER_ID SIZE FRAMES     # e.g. 35-raymarch 400x225 6

`--jit auto`: one frame of 36-raymarch at 128x72 on threads (its math passes auto's threshold,
so this process loads the kernels), then FRAMES frames of the real shader SHADER_ID
(tools/real_verify.py's texts) on two worker processes, each at a new iTime. Prints the wall
time of each frame (and how it was rendered: p = processes), the total wall time and the CPU
time of this process after the first shader plus the workers'. The workers load the kernels
before their first frame when the parent has (jit.decided), rather than each counting to its
own threshold. Run it from the checkout to measure (PYTHONPATH for another one).
"""

from __future__ import annotations

import os
import resource
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "tools"))
os.environ["GLSLCHECK_JIT"] = "auto"

import real_verify  # noqa: E402

from glslcheck.backends.numpy_engine import jit, workers  # noqa: E402
from glslcheck.backends.numpy_engine.program import compile_numpy  # noqa: E402
from glslcheck.shadertoy.sources import load_shader  # noqa: E402


def _program(manifest: dict, sid: str, parallel: str):
    prog = compile_numpy(load_shader(str(real_verify.text_path(manifest[sid]))))
    prog.parallel, prog.threads = parallel, 2
    return prog


def main(argv: list[str]) -> int:
    sid, size, frames = argv[0], tuple(int(v) for v in argv[1].split("x")), int(argv[2])
    manifest = {e["id"]: e for e in real_verify.load_manifest()}
    _program(manifest, "36-raymarch", "threads").render(size=(128, 72), time=1.7)
    if jit._STATE.kernels is None:
        print("the parent did not load the kernels (numba missing, or its threshold not reached)")
        return 1
    prog = _program(manifest, sid, "processes")
    c0, t0, walls = time.process_time(), time.perf_counter(), []
    for i in range(frames):
        prog._cache.clear()
        t = time.perf_counter()
        prog.render(size=size, time=1.7 + 0.01 * i)
        walls.append(f"{time.perf_counter() - t:.2f}{prog.last_parallel[0]}")
    total = time.perf_counter() - t0
    workers.shutdown()
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = time.process_time() - c0 + children.ru_utime + children.ru_stime
    print(
        f"{sid} {size[0]}x{size[1]} x{frames} on 2 workers after the parent loaded: "
        f"wall {total:.2f} s, "
        f"CPU (this process after the first shader + workers) {cpu:.2f} s; "
        f"frames {' '.join(walls)}; "
        f"load {os.getloadavg()[0]:.1f}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
