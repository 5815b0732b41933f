#!/usr/bin/env python3
"""Benchmark: type-checking time against parsing time on a ~300-line shader.

Uses the largest lab shader (Common + Image) and, when it is shorter than --lines, appends
generated helper functions (vector math, loops, structs, swizzles) until it is long enough.
Prints the median of --repeat runs of `parse_shader` (preprocess + parse + AST) and of `check`.
Target: checking adds at most 50% to parse time.

    python tools/bench_check.py [--lines 300] [--repeat 20]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from glslcheck.frontend.parser import parse_shader  # noqa: E402
from glslcheck.semantics import check  # noqa: E402
from glslcheck.shadertoy.sources import Source, load_shader  # noqa: E402

_HELPER = """
// generated helper {i}
float helper{i}(vec3 p, float k)
{{
    vec3 q = abs(p) - vec3(0.5 * k, 0.25, 1.0);
    float d = length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
    for (int j = 0; j < 4; j++)
    {{
        q.xy = mat2(0.8, -0.6, 0.6, 0.8) * q.xy;
        d = min(d, dot(q, q) - float(j) * 0.1);
    }}
    return d > 0.0 ? d : -d * k;
}}
"""


def largest_lab_shader():
    best = None
    for folder in sorted((ROOT / "lab_shaders").glob("*/")):
        shader = load_shader(folder)
        n = sum(s.text.count("\n") for s in shader.tabs.values())
        if best is None or n > best[0]:
            best = (n, shader)
    return best[1]


def make_shader(lines: int):
    shader = largest_lab_shader()
    image = shader.tabs["Image"]
    total = sum(s.text.count("\n") for s in shader.tabs.values())
    extra, i = [], 0
    while total < lines:
        chunk = _HELPER.format(i=i)
        extra.append(chunk)
        total += chunk.count("\n")
        i += 1
    shader.tabs["Image"] = Source(image.path, "".join(extra) + image.text, "Image")
    return shader, total


def timed(fn, repeat: int) -> tuple[float, object]:
    times, result = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), result


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--lines", type=int, default=300)
    p.add_argument("--repeat", type=int, default=20)
    args = p.parse_args(argv)
    shader, total = make_shader(args.lines)
    parse_shader(shader, "Image")  # warm the parser (tables loaded once per process)
    t_parse, result = timed(lambda: parse_shader(shader, "Image"), args.repeat)
    t_check, model = timed(lambda: check(result, "Image"), args.repeat)
    print(f"shader: {total} lines (Common + Image), {sum(1 for _ in result.ast.walk())} AST nodes")
    print(f"parse: {t_parse * 1000:.2f} ms (median of {args.repeat})")
    print(
        f"check: {t_check * 1000:.2f} ms (median of {args.repeat}) = "
        f"{100 * t_check / t_parse:.0f}% of parse time"
        f" (target <= 50%)"
    )
    return 0 if t_check <= 0.5 * t_parse else 1


if __name__ == "__main__":
    sys.exit(main())
