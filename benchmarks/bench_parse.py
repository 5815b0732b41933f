"""Benchmark: preprocess + parse + AST build of a ~300-line shader (warm, in process), and one
whole `glslcheck parse` CLI call on one file, with glslangValidator on the same program as the
reference run in the same process.

Targets: <= 30 ms warm parse; <= 0.3 s for the whole CLI call. Printed, not asserted:
timings are facts about a machine, not unit tests.

    python benchmarks/bench_parse.py [--runs N]
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from glslcheck.frontend.parser import parse_units  # noqa: E402
from glslcheck.shadertoy.sources import Source  # noqa: E402


def make_shader(target_lines: int = 300) -> str:
    """A realistic ~300-line shader: the corpus's lit scene repeated with renamed symbols."""
    base = (ROOT / "tests" / "corpus" / "spheres_phong.glsl").read_text()
    names = ["mainImage", "PointLight", "Sphere", "LIGHT_COUNT", "SHININESS", "hitSphere", "shade("]
    parts, i = [], 0
    while sum(p.count("\n") for p in parts) < target_lines:
        text = base
        for n in names:
            text = text.replace(n, n.rstrip("(") + f"_{i}" + ("(" if n.endswith("(") else ""))
        parts.append(text)
        i += 1
    text = "\n".join(parts)
    # Keep exactly one mainImage.
    return text.replace("mainImage_0", "mainImage")


def median_ms(fn, runs: int, clock=time.perf_counter) -> float:
    fn()  # warm-up: tables loaded, caches filled
    times = []
    for _ in range(runs):
        t = clock()
        fn()
        times.append(clock() - t)
    return statistics.median(times) * 1000


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=30)
    args = ap.parse_args()
    text = make_shader()
    lines = text.count("\n") + 1
    units = [Source("bench.glsl", text)]
    parse = median_ms(lambda: parse_units(units), args.runs)
    print(
        f"machine: {platform.machine()} {os.cpu_count()} cores, Python {platform.python_version()}"
    )
    cpu = median_ms(lambda: parse_units(units), args.runs, clock=time.process_time)
    print(
        f"load average: {os.getloadavg()[0]:.1f} (other processes on {os.cpu_count()} cores "
        "inflate wall times)"
    )
    print(
        f"warm preprocess+parse+AST, {lines} lines: {parse:.1f} ms wall, "
        f"{cpu:.1f} ms CPU (target <= 30 ms)"
    )
    try:
        from glslcheck.semantics import check

        parsed = parse_units(units)
        check_ms = median_ms(lambda: check(parsed), args.runs)
        print(
            f"check on top of parse: {check_ms:.1f} ms = {check_ms / parse:.0%} of parse (target "
            "<= 50%)"
        )
    except Exception as e:  # the checker may not accept the synthetic program yet
        print(f"check: not measured ({type(e).__name__}: {e})")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "Image.glsl"
        path.write_text(text)
        exe = shutil.which("glslcheck") or str(Path(sys.executable).with_name("glslcheck"))
        cli = []
        for _ in range(max(5, args.runs // 5)):
            t = time.perf_counter()
            subprocess.run([exe, "parse", "-q", str(path)], check=True)
            cli.append(time.perf_counter() - t)
        print(
            f"one CLI call `glslcheck parse` on one file: {statistics.median(cli):.3f} s (target "
            "<= 0.3 s)"
        )
        glslang = shutil.which("glslangValidator")
        if glslang:
            from glslcheck.shadertoy.sources import load_shader
            from glslcheck.shadertoy.wrapper import build_program

            prog = Path(tmp) / "prog.frag"
            prog.write_text(build_program(load_shader(path)).text)
            ref = []
            for _ in range(max(5, args.runs // 5)):
                t = time.perf_counter()
                subprocess.run([glslang, str(prog)], check=True, capture_output=True)
                ref.append(time.perf_counter() - t)
            g = statistics.median(ref)
            print(
                f"glslangValidator on the same program: {g:.3f} s; glslcheck parse CLI / glslang = "
                f"{statistics.median(cli) / g:.1f}x"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
