"""Benchmark: transpile time against nesting depth, for the shapes that used to reach
Python's limits or grow faster than linearly: nested ternaries (cubic before: 6 s at 150, 44 s
at 300), nested ifs (over 120 s at 500), else-if chains, nested parentheses and nested loops.

The reference run, in the same process, is a flat program with the same statements one after
another (`flat`): per level, a nested shape should cost a constant multiple of a flat statement
at every depth. Printed per depth: seconds, seconds per level, and the ratio to the flat program
of the same size. Near-linear means the per-level time (and the ratio) stays about constant as
the depth grows. Only the transpiler is timed (parse and check run before, untimed); best of
--runs. Printed, not asserted.

    python benchmarks/bench_transpile_depth.py [--runs 3] [--depths 25,50,100,200,400]
"""

from __future__ import annotations

import argparse
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from glslcheck.backends.numpy_engine.transpile import transpile  # noqa: E402
from glslcheck.base.diagnostics import register_source  # noqa: E402
from glslcheck.frontend.parser import parse_shader  # noqa: E402
from glslcheck.semantics import check  # noqa: E402
from glslcheck.shadertoy.sources import Shader, Source  # noqa: E402

MAIN = "void mainImage(out vec4 c, in vec2 p) {\n    float v = 0.0;\n    "
END = "\n    c = vec4(v);\n}\n"


def ternaries(n: int) -> str:
    e = "p.x"
    for k in range(n):
        e = f"(p.y > {k}.0 ? {e} : {k}.0)"
    return MAIN + f"v = {e};" + END


def ifs(n: int) -> str:
    return MAIN + "".join(f"if (p.x > {k % 7}.0) {{ v += 1.0; " for k in range(n)) + "}" * n + END


def else_ifs(n: int) -> str:
    return (
        MAIN
        + "if (p.x < 0.0) v = 0.0;"
        + "".join(f" else if (p.x < {k}.0) v = {k}.0;" for k in range(1, n))
        + END
    )


def parens(n: int) -> str:
    return MAIN + "v = " + "p.x + (" * n + "1.0" + ")" * n + ";" + END


def loops(n: int) -> str:
    return (
        MAIN
        + "".join(f"for (int i{k} = 0; i{k} < 1; i{k}++) {{ v += 1.0; " for k in range(n))
        + "}" * n
        + END
    )


def flat(n: int) -> str:
    """The reference: n statements of the kinds above, one after another."""
    return MAIN + "".join(f"if (p.x > {k % 7}.0) {{ v += 1.0; }}\n    " for k in range(n)) + END


SHAPES = {
    "ternaries": ternaries,
    "ifs": ifs,
    "else-ifs": else_ifs,
    "parens": parens,
    "loops": loops,
}


def transpile_seconds(text: str, runs: int) -> float:
    register_source("Image.glsl", text)
    shader = Shader(tabs={"Image": Source("Image.glsl", text, "Image")}, root="Image.glsl")
    model = check(parse_shader(shader, "Image"))
    best = float("inf")
    for _ in range(runs):
        t0 = time.perf_counter()
        transpile(model, "Image.glsl")
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--depths", default="25,50,100,200,400")
    args = p.parse_args()
    depths = [int(d) for d in args.depths.split(",")]
    print(
        f"# {platform.processor() or platform.machine()}, Python {platform.python_version()}; "
        f"best of {args.runs}"
    )
    print(f"{'shape':<10} {'depth':>6} {'seconds':>9} {'ms/level':>9} {'vs flat':>8}")
    ref = {n: transpile_seconds(flat(n), args.runs) for n in depths}
    for n in depths:
        print(f"{'flat':<10} {n:>6} {ref[n]:>9.3f} {1000 * ref[n] / n:>9.2f} {1.0:>8.2f}")
    for name, make in SHAPES.items():
        for n in depths:
            s = transpile_seconds(make(n), args.runs)
            print(f"{name:<10} {n:>6} {s:>9.3f} {1000 * s / n:>9.2f} {s / ref[n]:>8.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
