"""Resource limits: on each limit case glslcheck ends with a clear result, and its
peak memory and time stay bounded.

Each case runs `python -m glslcheck ...` in a child process and reads the child's own peak
resident memory (`os.wait4` rusage, no tracing overhead). The child is forked by a small
launcher process, not by pytest: Linux counts the memory of the process a child was forked
from into the child's peak (exec records the old address space's high-water mark), so a
child of the test process would report the test process's own size, which grows with the
tests that ran before (numba's compiler in tests/compiled: 979 MB). Bounds are deliberately
generous, so a loaded CI machine cannot make them flake:

- memory: a Python process with NumPy and the Lark tables is about 50-100 MB; a 1 MB shader's
  tokens, trees, AST and semantic model take about 300 MB more. 700 MB leaves room for that
  and still catches anything that grows with the expansion of macros, the nesting depth or the
  image size (a 16384x16384 image alone is 4 GiB).
- time: never a wall-clock threshold. Scaling is measured as a ratio between the same input
  at two sizes, 10x apart: linear work gives ~10 (start-up makes it less), quadratic work
  gives ~100. The bound is 35. A per-case `timeout` only stops a hang.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import pytest

from glslcheck.shadertoy.sources import MAX_FILE_BYTES

PEAK_MB = 700
RATIO = 35
HANG = 600  # seconds: a hang, not a slow machine


# The launcher: forks `python -m glslcheck ARGV`, waits for it, writes its peak RSS (KiB) to
# the file argv[1] and ends as it ended (the same exit code, or killed by the same signal).
_LAUNCHER = """\
import os, signal, sys
pid = os.fork()
if pid == 0:
    os.execv(sys.executable, [sys.executable, "-m", "glslcheck", *sys.argv[2:]])
_, status, usage = os.wait4(pid, 0)
with open(sys.argv[1], "w") as f:
    f.write(str(usage.ru_maxrss))
code = os.waitstatus_to_exitcode(status)
if code < 0:
    signal.signal(-code, signal.SIG_DFL)
    os.kill(os.getpid(), -code)
sys.exit(code)
"""


def measure(argv: list[str], cwd: Path) -> tuple[int, float, float, str]:
    """(exit code, seconds, peak RSS in MB, stderr) of `python -m glslcheck ARGV` in a child
    process; the peak is that child's own (os.wait4 in the launcher above, which the test kills
    with its whole process group after HANG seconds)."""
    with tempfile.TemporaryFile() as errf, tempfile.TemporaryDirectory() as tmp:
        peak_file = Path(tmp) / "peak"
        start = time.perf_counter()
        proc = subprocess.Popen(
            [sys.executable, "-c", _LAUNCHER, str(peak_file), *argv],
            cwd=cwd,
            stdout=subprocess.DEVNULL,
            stderr=errf,
            start_new_session=True,
        )
        timer = threading.Timer(HANG, os.killpg, (proc.pid, signal.SIGKILL))
        timer.start()
        try:
            rc = proc.wait()
        finally:
            timer.cancel()
        seconds = time.perf_counter() - start
        errf.seek(0)
        text = errf.read().decode("utf-8", "replace")
        assert rc != -9, f"glslcheck {' '.join(argv)} ran longer than {HANG} s"
        peak_mb = int(peak_file.read_text()) / 1024
    print(
        f"glslcheck {argv[0]} {Path(argv[1]).parent.name}/{Path(argv[1]).name}: exit {rc}, "
        f"{seconds:.1f} s, peak {peak_mb:.0f} MB"
    )  # shown with pytest -s
    assert "Traceback" not in text, text[-3000:]
    assert rc in (0, 1, 2), (rc, text[-2000:])
    return rc, seconds, peak_mb, text


def write(folder: Path, name: str, text: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def long_program(statements: int) -> str:
    body = "".join(f"    x = x * 0.5 + sin(p.x + {i % 1000}.0);\n" for i in range(statements))
    return (
        "void mainImage(out vec4 c, in vec2 p) {\n    float x = 0.0;\n"
        + body
        + "    c = vec4(x);\n}\n"
    )


def many_functions(n: int) -> str:
    fs = "".join(f"float f{i}(float x) {{ return x * {i % 7}.0 + 1.0; }}\n" for i in range(n))
    return (
        fs
        + f"void mainImage(out vec4 c, in vec2 p) {{ c = vec4(f{n - 1}(p.x), f0(1.0), 0.0, 1.0); "
        "}\n"
    )


def check_is_linear_and_bounded(tmp_path: Path, small: Path, big: Path, what: str) -> None:
    """`glslcheck check` accepts both; the 10x larger input peaks under PEAK_MB and takes under
    RATIO times as long as the small one."""
    rc, small_s, _, err = measure(["check", str(small)], tmp_path)
    assert rc == 0, err
    rc, big_s, peak, err = measure(["check", str(big)], tmp_path)
    assert rc == 0, err
    assert peak < PEAK_MB, f"check of {what} peaked at {peak:.0f} MB"
    assert big_s / small_s < RATIO, (
        f"10x took {big_s / small_s:.1f}x the time ({small_s:.1f} s -> {big_s:.1f} s)"
    )


def test_one_megabyte_file_is_linear_and_bounded(tmp_path):
    big = long_program(27000)
    assert 0.9 * MAX_FILE_BYTES < len(big) <= MAX_FILE_BYTES
    small_path = write(tmp_path / "small", "shader.glsl", long_program(2700))
    big_path = write(tmp_path / "big", "shader.glsl", big)
    check_is_linear_and_bounded(tmp_path, small_path, big_path, "a 1 MB file")
    rc, _, peak, err = measure(["lint", str(big_path)], tmp_path)
    assert rc in (0, 1) and peak < PEAK_MB, (rc, peak, err[-500:])


def test_file_over_the_limit_is_refused_without_reading_it(tmp_path):
    path = write(tmp_path, "shader.glsl", "// x\n" * (MAX_FILE_BYTES // 5 + 1))
    for command in ("parse", "check", "lint"):
        rc, _, _, err = measure([command, str(path)], tmp_path)
        assert rc == 2 and f"up to {MAX_FILE_BYTES} bytes" in err, err


def test_10000_functions_are_linear_and_bounded(tmp_path):
    small = write(tmp_path / "small", "shader.glsl", many_functions(1000))
    big = write(tmp_path / "big", "shader.glsl", many_functions(10000))
    # Without unique names and without GC during the parse the ratio was ~100.
    check_is_linear_and_bounded(tmp_path, small, big, "10,000 functions")


@pytest.mark.parametrize("shape", ["blocks", "parens", "calls", "ifs"])
def test_500_deep_nesting(tmp_path, shape):
    n = 500
    inner = {
        "blocks": "c = vec4(0.0); " + "{" * n + "}" * n,
        "parens": "c = vec4(" + "(" * n + "1.0" + ")" * n + ");",
        "calls": "c = vec4(" + "sin(" * n + "1.0" + ")" * n + ");",
        "ifs": "c = vec4(0.0); " + "if (p.x > 1.0) " * n + "c.x = 1.0;",
    }[shape]
    path = write(tmp_path, "shader.glsl", f"void mainImage(out vec4 c, in vec2 p) {{ {inner} }}\n")
    rc, _, peak, err = measure(["check", str(path)], tmp_path)
    assert rc == 0, err
    assert peak < PEAK_MB


def test_macro_bomb_stops_at_the_expansion_cap(tmp_path):
    # 2**40 tokens if expanded: the preprocessor's cap stops it with an error at the use.
    bomb = (
        "#define A0 x\n"
        + "".join(f"#define A{i + 1} A{i} A{i}\n" for i in range(40))
        + "void mainImage(out vec4 c, in vec2 p) { float x = 1.0; c = vec4(A40); }\n"
    )
    path = write(tmp_path, "shader.glsl", bomb)
    rc, _, peak, err = measure(["check", str(path)], tmp_path)
    assert rc == 1 and re.search(
        r"shader\.glsl:42:\d+: error: macro expansion is too large", err
    ), err
    assert peak < PEAK_MB


def test_self_referencing_macros_do_not_recurse(tmp_path):
    text = (
        "#define F(x) F(x) + G(x)\n#define G(x) F(x)\n"
        "void mainImage(out vec4 c, in vec2 p) { float x = 1.0; c = vec4(F(x)); }\n"
    )
    rc, _, _, err = measure(["check", str(write(tmp_path, "shader.glsl", text))], tmp_path)
    assert rc == 1 and "shader.glsl:3:" in err, err


@pytest.mark.parametrize(
    "loop",
    [
        "for (;;) { x += 1.0; }",
        "while (x >= 0.0) { x += 1.0; }",
        "for (int i = 0; i < 2000000000; i++) { x += 1.0; }",
    ],
)
def test_endless_loop_stops_at_the_documented_cap(tmp_path, loop):
    text = f"void mainImage(out vec4 c, in vec2 p) {{ float x = 0.0; {loop} c = vec4(x); }}\n"
    path = write(tmp_path, "shader.glsl", text)
    rc, _, peak, err = measure(
        ["render", str(path), "--size", "8x8", "-o", str(tmp_path / "o.npy")], tmp_path
    )
    assert rc == 1 and re.search(r"shader\.glsl:1:\d+: error: this loop did not end", err), err
    assert peak < PEAK_MB


@pytest.mark.parametrize("command", ["render", "verify"])
def test_huge_size_is_refused(tmp_path, command):
    path = write(
        tmp_path, "shader.glsl", "void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n"
    )
    extra = ["-o", str(tmp_path / "o.npy")] if command == "render" else []
    rc, _, _, err = measure([command, str(path), "--size", "16384x16384", *extra], tmp_path)
    assert rc == 2 and "at most 16,777,216 pixels" in err, err
