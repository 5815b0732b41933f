"""Hostile but valid programs against the NumPy backend: Python's own limits reached
through the generated code, runaway work, memory, and signals.

- Python's limits: CPython refuses 20+ nested loops in one function ("too many statically
  nested blocks"), 100 indentation levels and 200 nested brackets. Each shape below used to
  fail with a SyntaxError/IndentationError traceback (or, for 300 nested ternaries, spent 40 s
  transpiling); now the program transpiles to code Python compiles and renders the values a
  hand-written NumPy reference gives (the reference applies the same float32 operations in the
  same order, so the comparison is exact).
- Runaway work: the per-loop cap lets nested loops run 99,999**2 times; the frame budget
  (GLSLCHECK_FRAME_SECONDS) stops them with an error at the loop.
- Memory: `float a[1000000]` needs 4 MB per pixel; tiles are sized to GLSLCHECK_MEMORY_MB, or
  the shader is refused at the declaration when even a 2x2 tile does not fit.
- Signals: Ctrl-C stops a thread render, and worker processes die with a killed parent.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from test_robustness_resources import PEAK_MB, RATIO, measure, write

from glslcheck.backends.numpy_engine import program as P
from glslcheck.backends.numpy_engine import tiles as F
from glslcheck.backends.numpy_engine.transpile import compile_generated, transpile
from glslcheck.base.diagnostics import GlslError
from glslcheck.shadertoy.sources import load_shader

MAIN = "void mainImage(out vec4 c, in vec2 p) {\n"

# 99,999**2 iterations per pixel: hours at any size without a frame budget
RUNAWAY = MAIN + (
    "    float x = 0.0;\n    for (int i = 0; i < 99999; i++) {\n"
    "        for (int j = 0; j < 99999; j++) { x += 1.0; }\n    }\n    c = vec4(x);\n}\n"
)


def render(tmp_path: Path, text: str, size: tuple[int, int], **kw) -> np.ndarray:
    """The red channel of the NumPy render, row 0 = the bottom row (p.y = 0.5)."""
    prog = P.compile_numpy(load_shader(str(write(tmp_path, "shader.glsl", text))))
    for line in prog.source.splitlines():  # within Python's limits with room to spare
        assert len(line) - len(line.lstrip(" ")) < 4 * 80, line[:120]
    return prog.render(size=size, **kw)[::-1, :, 0]


def pixel_x(size: tuple[int, int]) -> np.ndarray:
    return np.broadcast_to(np.arange(size[0], dtype=np.float32) + np.float32(0.5), size[::-1])


# --- Python's limits ---------------------------------------------------------------------------


def test_21_nested_loops(tmp_path):
    """'too many statically nested blocks': the 17th loop on goes to a helper function."""
    n = 21
    counts = [1] * (n - 2) + [2, 3]
    loops = "".join(f"for (int i{k} = 0; i{k} < {m}; i{k}++) {{ " for k, m in enumerate(counts))
    text = (
        MAIN + f"    float x = 0.0;\n    {loops}x += 1.0; if (p.x < 4.0) break; "
        f"{'}' * n}\n    c = vec4(x);\n}}\n"
    )
    size = (8, 2)
    # the innermost loop (3 iterations) breaks after one where p.x < 4; the one around it runs twice
    assert np.array_equal(render(tmp_path, text, size), np.where(pixel_x(size) < 4, 2.0, 6.0))


def test_250_nested_parentheses(tmp_path):
    """'too many nested parentheses': every SPILL_HEIGHT levels go to a temporary."""
    n = 250
    text = MAIN + "    c = vec4(" + "p.x + (" * n + "1.0" + ")" * n + ");\n}\n"
    size = (8, 2)
    x = pixel_x(size)
    want = np.ones_like(x)
    for _ in range(n):  # innermost first, as GLSL evaluates it
        want = x + want
    assert np.array_equal(render(tmp_path, text, size), want)


def test_300_nested_ternaries(tmp_path):
    """Too many nested parentheses, and 40 s of transpiling (has_effects walked every subtree
    at every level: cubic)."""
    n = 300
    e = "p.x"
    for k in range(n):
        e = f"(p.x > {k}.0 ? {e} : {k}.0)"
    size = (320, 2)
    x = pixel_x(size)
    want = x
    for k in range(n):
        want = np.where(x > k, want, np.float32(k))
    assert np.array_equal(render(tmp_path, MAIN + f"    c = vec4({e});\n}}\n", size), want)


@pytest.mark.parametrize("on", ["p.x", "iTime"])
def test_else_if_chain_of_100_branches(tmp_path, on):
    """'too many levels of indentation': each else nests one level deeper; branches on a
    varying value (masks) and on a uniform one (plain Python if/else)."""
    n = 100
    chain = f"if ({on} < 1.0) v = 1.0;" + "".join(
        f" else if ({on} < {k + 1}.0) v = {k + 1}.0;" for k in range(1, n)
    )
    text = MAIN + f"    float v = 0.0;\n    {chain} else v = -1.0;\n    c = vec4(v);\n}}\n"
    size = (128, 2)
    if on == "p.x":
        x = pixel_x(size)
        want = np.where(x < n, np.floor(x) + 1, -1.0)
        assert np.array_equal(render(tmp_path, text, size), want)
    else:
        for t, v in ((0.5, 1.0), (57.5, 58.0), (99.5, 100.0), (100.5, -1.0)):
            assert np.all(render(tmp_path, text, size, time=t) == v), t


def test_500_nested_ifs_with_statements(tmp_path):
    n = 500
    body = "".join(f"if (p.x > {k % 7}.0) {{ v += 1.0; " for k in range(n)) + "}" * n
    text = MAIN + f"    float v = 0.0;\n    {body}\n    c = vec4(v);\n}}\n"
    size = (8, 2)
    x = pixel_x(size)
    levels = np.array(
        [next((k for k in range(n) if not xv > k % 7), n) for xv in x[0]], dtype=np.float32
    )
    assert np.array_equal(render(tmp_path, text, size), np.broadcast_to(levels, x.shape))


def test_300_nested_short_circuits(tmp_path):
    """`&&` with a non-trivial right side nests one `if X.live(...)` per level: the expression
    is outlined into helper functions past OUTLINE_EXPR_INDENT."""
    n = 300
    e = "".join(f"p.x > float({k % 5}) && (" for k in range(n)) + "true" + ")" * n
    text = MAIN + f"    bool b = {e};\n    c = vec4(b ? 1.0 : 0.0);\n}}\n"
    size = (8, 2)
    assert np.array_equal(render(tmp_path, text, size), np.where(pixel_x(size) > 4, 1.0, 0.0))


def test_declaration_in_a_block_inside_a_case(tmp_path):
    """Found by the hostile fuzzer: a declaration in a block inside a switch case was written
    as a masked update of a variable that had never been bound (UnboundLocalError)."""
    text = MAIN + (
        "    float x = 0.0;\n    switch (int(p.x) % 2) {\n"
        "    case 0: { int w = 3; x += float(w); } break;\n    default: x = 2.0;\n    }\n"
        "    c = vec4(x);\n}\n"
    )
    size = (8, 2)
    assert np.array_equal(
        render(tmp_path, text, size), np.where(np.floor(pixel_x(size)) % 2 == 0, 3.0, 2.0)
    )


def test_masked_writes_to_arrays_at_varying_indices(tmp_path):
    """Arrays of more than 4 elements are written with one scatter (it was one pass per
    element: a[4000000] took 50 s in one call). Reference: the same writes in NumPy."""
    text = MAIN + (
        "    float a[9];\n    for (int i = 0; i < 9; i++) a[i] = float(i);\n"
        "    if (p.x > 3.0) a[int(p.x) % 9] = 20.0;\n    a[int(p.x + 2.0) % 9] += 100.0;\n"
        "    c = vec4(a[int(p.x) % 9] + 1000.0 * a[int(p.x + 2.0) % 9]);\n}\n"
    )
    size = (16, 2)
    got = render(tmp_path, text, size)
    for col, xv in enumerate(pixel_x(size)[0]):
        a = np.arange(9, dtype=np.float32)
        if xv > 3:
            a[int(xv) % 9] = 20
        a[int(xv + 2) % 9] += 100
        assert np.all(got[:, col] == a[int(xv) % 9] + 1000 * a[int(xv + 2) % 9]), col


def test_what_python_still_refuses_is_a_located_error():
    """The safety net: code Python cannot compile is an error at the GLSL line of the nearest
    `# line N` comment, not a SyntaxError traceback."""
    source = (
        "def f(S):\n    # line 7: x = (((...)));\n    x = " + "(" * 300 + "1" + ")" * 300 + "\n"
    )
    with pytest.raises(GlslError) as e:
        compile_generated(source, "<test>", "shader.glsl")
    d = e.value.diagnostics[0]
    assert (d.loc.path, d.loc.line) == ("shader.glsl", 7)
    assert "too complex to render on the CPU" in d.message


def test_1200_deep_call_chain_is_a_located_error(tmp_path):
    """GLSL has no recursion, but a chain of 1200 functions each calling the previous one
    reaches Python's recursion limit while rendering: an error at a function of the chain."""
    n = 1200
    text = "float f0(float v) { return v * 0.5; }\n" + "".join(
        f"float f{k}(float v) {{ return f{k - 1}(v) + 1.0; }}\n" for k in range(1, n)
    )
    text += MAIN + f"    c = vec4(f{n - 1}(p.x));\n}}\n"
    prog = P.compile_numpy(load_shader(str(write(tmp_path, "shader.glsl", text))))
    with pytest.raises(GlslError) as e:
        prog.render(size=(4, 2))
    d = e.value.diagnostics[0]
    assert "too complex to render on the CPU" in d.message and d.loc.path.endswith("shader.glsl")
    assert 1 <= d.loc.line <= n, d


@pytest.mark.parametrize("shape", ["ternaries", "ifs"])
def test_transpile_time_is_near_linear_in_the_depth(tmp_path, make_shader, shape):
    """Transpiling 10x deeper takes under RATIO (35) times as long (linear: ~10; the ternaries
    were cubic: 6 s at 150, 44 s at 300). A ratio on the same machine, not a time."""
    from glslcheck.frontend.parser import parse_shader
    from glslcheck.semantics import check

    def seconds(n: int) -> float:
        if shape == "ternaries":
            e = "p.x"
            for k in range(n):
                e = f"(p.y > {k}.0 ? {e} : {k}.0)"
            text = MAIN + f"    c = vec4({e});\n}}\n"
        else:
            text = (
                MAIN
                + "    float v = 0.0;\n    "
                + "".join(f"if (p.x > {k % 7}.0) {{ v += 1.0; " for k in range(n))
                + "}" * n
                + "\n    c = vec4(v);\n}\n"
            )
        model = check(parse_shader(make_shader(text), "Image"))
        best = float("inf")
        for _ in range(3):
            t0 = time.perf_counter()
            transpile(model, "Image.glsl")
            best = min(best, time.perf_counter() - t0)
        return best

    small, big = seconds(40), seconds(400)
    assert big / small < RATIO, (
        f"10x deeper took {big / small:.1f}x as long ({small:.3f} s -> {big:.3f} s)"
    )


# --- runaway work ------------------------------------------------------------------------------


@pytest.mark.parametrize("parallel", ["threads", "processes"])
def test_nested_runaway_loops_stop_at_the_frame_budget(tmp_path, parallel):
    prog = P.compile_numpy(load_shader(str(write(tmp_path, "shader.glsl", RUNAWAY))))
    prog.frame_seconds = 1.0
    prog.parallel = parallel
    with pytest.raises(GlslError) as e:
        prog.render(size=(64, 64))
    d = e.value.diagnostics[0]
    assert d.rule == "numpy-frame-budget" and "still rendering after 1 s" in d.message
    assert d.loc.path.endswith("shader.glsl") and d.loc.line in (4, 5), d  # one of the two loops


def test_frame_budget_from_the_environment(tmp_path):
    path = write(tmp_path, "shader.glsl", RUNAWAY)
    out = ["-o", str(tmp_path / "o.npy")]
    env = {**os.environ, "GLSLCHECK_FRAME_SECONDS": "1"}
    r = subprocess.run(
        [sys.executable, "-m", "glslcheck", "render", str(path), "--size", "32x32", *out],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert r.returncode == 1 and re.search(
        r"shader\.glsl:[45]:\d+: error: the frame was still rendering", r.stderr
    ), r.stderr
    env["GLSLCHECK_FRAME_SECONDS"] = "soon"
    r = subprocess.run(
        [sys.executable, "-m", "glslcheck", "render", str(path), *out],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert (
        r.returncode == 2 and "GLSLCHECK_FRAME_SECONDS must be a number of seconds" in r.stderr
    ), r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.parametrize("text", ["1e9", "0.001", "0", "-5", "inf", "nan"])
def test_frame_budget_from_the_environment_takes_the_option_range(monkeypatch, text):
    """GLSLCHECK_FRAME_SECONDS is held to --frame-budget's range (0.01 to 86400 s): a budget of
    31 years is no budget, and 1 ms is below the timer's resolution."""
    from glslcheck.backends.numpy_engine.program import frame_seconds
    from glslcheck.base.diagnostics import InputError

    monkeypatch.setenv("GLSLCHECK_FRAME_SECONDS", text)
    with pytest.raises(InputError, match="from 0.01 to 86400"):
        frame_seconds()
    monkeypatch.setenv("GLSLCHECK_FRAME_SECONDS", "86400")
    assert frame_seconds() == 86400.0


# --- memory ------------------------------------------------------------------------------------

BIG_ARRAY = MAIN + (
    "    float a[1000000];\n    a[int(p.x)] = 1.0;\n"
    "    c = vec4(a[int(p.y)], a[int(p.x)], 0.0, 1.0);\n}\n"
)


def test_huge_array_is_refused_when_a_2x2_tile_does_not_fit(tmp_path, monkeypatch):
    path = write(tmp_path, "shader.glsl", BIG_ARRAY)
    monkeypatch.setenv("GLSLCHECK_MEMORY_MB", "20")
    r = subprocess.run(
        [sys.executable, "-m", "glslcheck", "render", str(path), "-o", str(tmp_path / "o.npy")],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert r.returncode == 1, r.stderr
    assert re.search(
        r"shader\.glsl:2:11: error: this shader needs about 11 MB per pixel", r.stderr
    ), r.stderr


def test_huge_array_renders_in_small_tiles_within_the_budget(tmp_path, monkeypatch):
    """1,000,000 floats per pixel at 16x16 is 1 GB per copy of the array in one tile (and it
    was: peak over 2 GB); with a 100 MB budget the tiles hold 4 pixels."""
    path = write(tmp_path, "shader.glsl", BIG_ARRAY)
    monkeypatch.setenv("GLSLCHECK_MEMORY_MB", "100")
    rc, _, peak, err = measure(
        ["render", str(path), "--size", "16x16", "-o", str(tmp_path / "o.npy")], tmp_path
    )
    assert rc == 0, err
    assert peak < PEAK_MB, f"peak {peak:.0f} MB"
    img = np.load(tmp_path / "o.npy")[::-1]
    x = pixel_x((16, 16))
    assert np.array_equal(img[..., 1], np.ones_like(x)) and np.array_equal(
        img[..., 0], np.where(np.floor(x.T) == np.floor(x), 1.0, 0.0)
    )


def test_tiles_respect_a_lane_limit():
    for w, h, lanes in ((64, 64, 40), (800, 450, 1000), (7, 5, 4), (3000, 2, 9)):
        tiles = F.frame_tiles(w, h, lanes)
        cover = np.zeros((h, w), dtype=int)
        for x0, y0, tw, th in tiles:
            assert tw * th <= max(lanes, F.MIN_TILE_LANES) and x0 % 2 == 0 and y0 % 2 == 0
            cover[y0 : y0 + th, x0 : x0 + tw] += 1
        assert np.all(cover == 1), (w, h, lanes)


# --- signals -----------------------------------------------------------------------------------


def _start_render(tmp_path: Path, parallel: str) -> subprocess.Popen:
    path = write(tmp_path, "shader.glsl", RUNAWAY)
    env = {**os.environ, "GLSLCHECK_PARALLEL": parallel}
    return subprocess.Popen(
        [
            sys.executable,
            "-m",
            "glslcheck",
            "render",
            str(path),
            "--size",
            "400x300",
            "-o",
            str(tmp_path / "o.npy"),
        ],
        env=env,
        stderr=subprocess.PIPE,
        text=True,
    )


def _children(pid: int) -> list[int]:
    out = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == pid:
                out.append(int(d))
    return out


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_ctrl_c_stops_a_thread_render(tmp_path):
    """The caller used to wait for every running tile (hours here) before seeing Ctrl-C."""
    proc = _start_render(tmp_path, "threads")
    try:
        time.sleep(5)  # started and rendering
        t0 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=60)  # a hang, not a slow machine: it stops within a second when idle
        print(f"stopped {time.monotonic() - t0:.2f} s after SIGINT")
        assert proc.returncode == 2 and "interrupted" in proc.stderr.read()
    finally:
        proc.kill()
        proc.wait()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="worker processes need Linux")
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_workers_die_with_their_parent(tmp_path, sig):
    """They used to stay at 100% CPU, orphaned, after the parent was killed."""
    proc = _start_render(tmp_path, "processes")
    workers: list[int] = []
    try:
        deadline = time.monotonic() + 120
        while len(workers) < 1 and time.monotonic() < deadline:
            time.sleep(0.5)
            workers = _children(proc.pid)
        assert workers, "no worker process started"
        time.sleep(2)  # inside the frame
        proc.send_signal(sig)
        proc.wait(timeout=60)
        deadline = time.monotonic() + 30
        while any(_alive(w) for w in workers) and time.monotonic() < deadline:
            time.sleep(0.2)
        assert not any(_alive(w) for w in workers), "a worker outlived its parent"
    finally:
        proc.kill()
        proc.wait()
        for w in workers:
            if _alive(w):
                os.kill(w, signal.SIGKILL)
