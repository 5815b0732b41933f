"""Time `verify` of one lab shader at 320x180 (target: <= 2 s wall, compile included).

    python tools/bench_verify.py [SHADER] [--size 320x180] [--repeat 3]

Prints the wall time of a cold verify (both compiles, both renders, the comparison) and of a
warm one (programs compiled: renders and comparison only), best of --repeat.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from glslcheck.base.limits import parse_size  # noqa: E402
from glslcheck.shadertoy.sources import load_shader  # noqa: E402
from glslcheck.verification.verify import compile_backend, verify  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("shader", nargs="?", default=str(ROOT / "lab_shaders" / "07_final"))
    ap.add_argument("--size", type=parse_size, default=(320, 180))
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    compile_backend(load_shader(args.shader), "gl")  # create the GL context outside the timing

    cold = []
    for _ in range(args.repeat):
        shader = load_shader(args.shader)
        t0 = time.perf_counter()
        c = verify(shader, size=args.size, time=1.0)[0]
        cold.append(time.perf_counter() - t0)
    shader = load_shader(args.shader)
    programs = [compile_backend(shader, "numpy"), compile_backend(shader, "gl")]
    warm = []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        verify(shader, size=args.size, time=1.0, programs=programs)
        warm.append(time.perf_counter() - t0)
    w, h = args.size
    print(
        f"verify {args.shader} {w}x{h}: {min(cold):.3f} s wall (compile + render + compare), "
        f"{min(warm):.3f} s warm (render + compare); {'match' if c.match else 'MISMATCH'}; "
        f"target <= 2 s: {'ok' if min(cold) <= 2.0 else 'OVER'}"
    )
    return 0 if min(cold) <= 2.0 else 1


if __name__ == "__main__":
    sys.exit(main())
