"""The benchmark scripts in benchmarks/ still run and print every figure they promise.

One quick round each (timings are not asserted: they are facts about a machine, see the
scripts' docstrings); what is checked is that each section prints its lines, so a refactoring
of the backends cannot silently break the scripts whose output the docs quote.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _run(script: str, *args: str, timeout: int = 240) -> str:
    done = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / script), *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert "Traceback" not in done.stderr
    return done.stdout


def test_bench_parse_prints_its_figures(glslang):
    out = _run("bench_parse.py", "--runs", "1")
    for line in (
        "warm preprocess+parse+AST",
        "check on top of parse",
        "one CLI call `glslcheck parse`",
        "glslangValidator on the same program",
    ):
        assert line in out, out


@pytest.mark.parametrize("args", [("--repeat", "1")])
def test_bench_render_prints_its_figures(gl, args):
    out = _run("bench_render.py", *args)
    for line in (
        "four spheres, four lights",
        "lab 07_final",
        "numpy processes",
        "threads",
        "time(small) / time(large) on processes",
        "one-thread CPU",
        "llvmpipe for reference",
        "threads  : render",
        "processes: render",
        "(limit 2048 MiB)",
    ):
        assert line in out, out


def test_run_all_prints_every_section(gl, glslang):
    out = _run("run_all.py", "--runs", "1", "--skip-memory")
    for line in (
        "1. parse + check against glslangValidator",
        "2. NumPy (float32, 1 sample) against GL",
        "3. coverage scaling",
        "processes: time(small) / time(large)",
        "threads: time(small) / time(large)",
        "gl: time(small) / time(large)",
    ):
        assert line in out, out


def test_bench_startup_prints_its_figures(glslang):
    out = _run("bench_startup.py", "--runs", "1", "--only", "venv")
    for line in (
        "lint FILE (",
        "check FILE (",
        "lint lab_shaders (34 programs)",
        "check lab_shaders (34 programs)",
        "python -c pass",
        "ratio (CPU)",
    ):
        assert line in out, out


def test_ab_lanes_math_prints_its_figures(numba):
    """The working tree's lanes_math.py against itself (a file path as --rev, so no git history is
    needed): the same bits, and a line of times."""
    lanes_math = ROOT / "glslcheck" / "backends" / "compiled_engine" / "lanes_math.py"
    out = _run(
        "ab_lanes_math.py",
        "--rev",
        str(lanes_math),
        "--size",
        "16x8",
        "--repeat",
        "1",
        str(ROOT / "lab_shaders" / "05_blinn_phong"),
        timeout=600,
    )
    assert "05_blinn_phong" in out and "same bits True" in out and "after/before" in out, out


def test_bench_lockstep_compile_tells_the_runtime_apart(numba, tmp_path):
    """Per pixel, after the warm-up child (01_spheres_procedural): that shader's module compiles
    with every runtime function it calls cached (no runtime seconds), bonus_animated_lights's
    compiles sin and cos, which the warm-up never called (runtime seconds counted)."""
    import json
    import re

    def calls_trig(shader: str) -> bool:
        text = "".join(p.read_text() for p in (ROOT / "lab_shaders" / shader).glob("*.glsl"))
        return re.search(r"\b(sin|cos)\s*\(", text) is not None

    assert not calls_trig("01_spheres_procedural") and calls_trig("bonus_animated_lights")
    out = tmp_path / "rows.json"
    _run(
        "bench_lockstep_compile.py",
        "--groups",
        "lab",
        "--lanes",
        "0",
        "--only",
        "01_spheres_procedural,bonus_animated_lights",
        "--json",
        str(out),
        timeout=600,
    )
    rows = {r["shader"]: r for r in json.loads(out.read_text())}
    assert rows["01_spheres_procedural"]["runtime"] == 0.0, rows
    animated = rows["bonus_animated_lights"]
    assert 0.0 < animated["runtime"] < animated["cpu"], rows
