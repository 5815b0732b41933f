"""numba's compiles beside the frames (CompiledProgram.build_apart): in a child process whose
machine code this process then loads from numba's cache, and stopped at a budget.

Each test has a numba cache of its own (a temporary $NUMBA_CACHE_DIR), so the child really
compiles and no test's machine code or verdict reaches another test or the user's cache.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest
from image_bits import assert_same

import glslcheck
from glslcheck.backends import tiered
from glslcheck.backends.compiled_engine import engine

SIZE = (24, 16)

SHADER = """
float ring(vec2 p) { return smoothstep(0.3, 0.28, abs(length(p) - 0.3)); }
void mainImage(out vec4 c, in vec2 f) {
    vec2 p = (f - 0.5 * iResolution.xy) / iResolution.y;
    c = vec4(ring(p), 0.5 + 0.5 * sin(iTime + p.x), p.y, %s);
}
"""


def _shader(make_shader, alpha: str):
    """A shader of its own per test: a module this process loaded once is never built again."""
    return make_shader(SHADER % alpha)


@pytest.fixture
def own_cache(monkeypatch, tmp_path):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    monkeypatch.delenv("GLSLCHECK_TIERS", raising=False)
    yield tmp_path
    # numba's config follows the environment again at the next use_cache_dir (a changed value)


def _same_as_numpy(shader, prog, time: float, name: str) -> None:
    """`prog`'s frame at iTime `time` is the NumPy backend's bits (a NaN any NaN)."""
    want = glslcheck.compile(shader, backend="numpy").render(size=SIZE, time=time)
    got = prog.render(size=SIZE, time=time)
    assert_same(got, want, what=f"iTime {time}", names=(name, "numpy"), mode="bits_any_nan")


def test_the_child_compiles_and_this_process_loads_its_machine_code(numba, make_shader, own_cache):
    shader = _shader(make_shader, "1.0")
    prog, _ = engine.generate(shader, lanes=0)
    prog = engine.CompiledProgram(prog, "Image.glsl")
    assert not engine.module_cached(prog.key)
    assert prog.build_apart(600.0) == ""
    assert engine.module_cached(prog.key)  # the child wrote numba's cache
    assert prog.compile_seconds() is not None  # and what its compile took
    prog.load(bounded=False)
    assert prog.cold is False  # loaded, not compiled here
    _same_as_numpy(shader, prog, 0.7, "compiled")
    assert prog.build_apart(600.0) == ""  # in the cache already: no child


def test_a_build_past_its_budget_is_stopped(numba, make_shader, own_cache):
    prog, _ = engine.generate(_shader(make_shader, "0.5 + 0.5"), lanes=0)
    prog = engine.CompiledProgram(prog, "Image.glsl")
    # (a child cannot start Python, import numba and compile in a hundredth of a second)
    assert prog.build_apart(0.01) == "over budget"
    assert not engine.module_cached(prog.key)


def test_a_lockstep_build_over_budget_is_never_tried_again(
    numba, make_shader, own_cache, monkeypatch
):
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    shader = _shader(make_shader, "0.25 + 0.75")
    prog = engine.compile_compiled(shader)
    assert isinstance(prog, engine.TieredProgram)
    prog.render(size=SIZE, time=0.5)  # the per-pixel module, compiled here
    monkeypatch.setattr(engine, "LOCKSTEP_BUDGET", 0.01)
    monkeypatch.setattr(engine.TieredProgram, "move_cost", lambda self: 0.0)
    assert prog.move_now() and prog.settle(600)
    assert prog.stay and prog.mode == "pixel" and prog.over_budget()
    monkeypatch.undo()  # the real budget and rule, the same cache
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(own_cache / "numba"))
    again = engine.compile_compiled(shader)
    assert again.over_budget() and again.move_cost() == float("inf")
    assert not again.move_now()


def test_the_default_program_stays_on_numpy_past_the_budget(
    numba, make_shader, own_cache, monkeypatch
):
    monkeypatch.setattr(tiered, "COMPILE_GUESS_SECONDS", 0.0)
    monkeypatch.setattr(tiered, "CACHED_LOAD_SECONDS", 0.0)
    monkeypatch.setattr(engine, "PIXEL_BUDGET", 0.01)
    monkeypatch.setattr(
        tiered.TieredCpuProgram, "_record_path", lambda self: str(own_cache / "t.tier")
    )
    shader = _shader(make_shader, "0.125 + 0.875")
    prog = glslcheck.compile(shader)
    prog.render(size=SIZE, time=0.5)
    assert prog.impl.settle(600)
    assert prog.impl.mode == "numpy" and prog.impl.stay.startswith("over budget")
    assert prog.impl.record()["verdict"] == prog.impl.stay  # kept: not tried again
    _same_as_numpy(shader, prog, 0.6, "auto")
    assert prog.engine == "numpy"


def test_a_compile_whose_asking_process_is_gone_ends(numba, make_shader, own_cache):
    """The child watches the process that asked for it (build.py): with that one gone (here: a
    process id that is not its parent), it ends at once instead of compiling for nobody."""
    prog, _ = engine.generate(_shader(make_shader, "0.0625 + 0.9375"), lanes=0)
    file = own_cache / "m.py"
    file.write_text(prog)
    child = subprocess.run(
        [sys.executable, "-m", "glslcheck.backends.compiled_engine.build", str(file), "x", "1"],
        env=dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path)),
        capture_output=True,
        timeout=120,
    )
    assert child.returncode == 1 and not child.stderr  # ended by the watch, not by an error


def test_a_compile_left_to_finish_goes_on_and_marks_its_module(numba, make_shader, own_cache):
    """A child whose parent left it to finish (the file MARKER.finish) goes on when the parent
    is gone, and writes the module's key into MARKER once numba's cache holds it."""
    source, _ = engine.generate(_shader(make_shader, "0.03125 + 0.96875"), lanes=0)
    prog = engine.CompiledProgram(source, "Image.glsl")
    file = own_cache / "m.py"
    file.write_text(source)
    marker = own_cache / "m.lanes8"
    (own_cache / "m.lanes8.finish").write_text("")
    child = subprocess.run(
        [sys.executable, "-m", "glslcheck.backends.compiled_engine.build", str(file), "x", "1"]
        + ["600", str(marker)],
        env=dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path)),
        capture_output=True,
        timeout=600,
    )
    assert child.returncode == 0, child.stderr
    assert marker.read_text() == prog.key + "\n"
    assert not (own_cache / "m.lanes8.finish").exists()
    assert engine.module_cached(prog.key)


def test_a_paid_lockstep_compile_outlives_its_process(numba, own_cache, tmp_path):
    """A process that ends while the lockstep compile it paid for runs leaves it to finish: the
    marker says over budget meanwhile, then the module's key, and a later program starts on
    that module with no compile of its own."""
    shader = tmp_path / "ring.glsl"  # (a file: the script below loads it)
    shader.write_text(SHADER % "0.015625 + 0.984375")
    script = tmp_path / "leave.py"
    script.write_text(
        "import sys, glslcheck\n"
        "from glslcheck.backends.compiled_engine import engine\n"
        "prog = engine.compile_compiled(sys.argv[1])\n"
        "prog.render(size=(24, 16), time=0.5)\n"  # the per-pixel module, compiled here
        "engine.TieredProgram.move_cost = lambda self: 0.0\n"
        "assert prog.move_now()\n"
        "while not engine._CHILDREN: prog.settle(0.05)\n"  # its compile under way,
        "print(prog._marker(), flush=True)\n"  # the process ends
    )
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    env.pop("GLSLCHECK_COMPILED_LANES", None)
    out = subprocess.run(
        [sys.executable, str(script), str(shader)], env=env, capture_output=True, timeout=600
    )
    assert out.returncode == 0, out.stderr
    marker = out.stdout.decode().strip().splitlines()[-1]
    deadline = time.monotonic() + 600
    text = ""
    while time.monotonic() < deadline:
        text = open(marker).read()
        if not text.startswith(engine.OVER):
            break
        time.sleep(0.5)
    later = engine.compile_compiled(str(shader))
    assert text.strip() and not later.over_budget()
    assert later.load_cached() and later.mode == "lanes8"
    assert not os.path.exists(os.path.join(os.path.dirname(marker), engine.FINISHING))


def test_a_compile_left_to_finish_says_how_it_ended(numba, make_shader, own_cache, monkeypatch):
    """While a child left to finish compiles, its marker holds off every other process (over
    budget, with its pid); a child gone without a word (killed, the machine restarted) leaves the
    compile to a later process; one stopped by its budget (SIGXCPU) says over budget for good."""
    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    prog = engine.compile_compiled(_shader(make_shader, "0.0078125 + 0.9921875"))
    marker = prog._marker()
    os.makedirs(os.path.dirname(marker), exist_ok=True)
    gone = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], stdout=-1)
    for pid, over in ((os.getpid(), True), (int(gone.stdout), False)):
        with open(marker, "w") as f:
            f.write(f"{engine.OVER} 30 s: {engine.LEFT_TO_FINISH} {pid}\n")
        again = engine.compile_compiled(_shader(make_shader, "0.0078125 + 0.9921875"))
        assert again.over_budget() is over, pid
    stop = subprocess.run(
        [
            sys.executable,
            "-c",
            "import sys; from glslcheck.backends.compiled_engine import build; "
            "build._LEFT.append(True); build._over(sys.argv[1], 30.0)",
            marker,
        ],
        env=dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path)),
        timeout=120,
    )
    assert stop.returncode == 1
    assert open(marker).read() == f"{engine.OVER} 30 s\n"
    assert engine.compile_compiled(_shader(make_shader, "0.0078125 + 0.9921875")).over_budget()


def test_a_build_s_budget_is_its_cpu_time():
    """A build waiting on a loaded machine is not stopped for the time it waits: a child that
    sleeps past its budget ends by itself, one that computes past it is stopped, and one that
    waits past WALL_FACTOR times it is stopped as starved, not over budget."""
    from glslcheck.backends.compiled_engine.budget import OVER, STARVED, WALL_FACTOR, wait_child

    sleeps = subprocess.Popen(
        [sys.executable, "-c", "import time; time.sleep(1.5)"], stderr=subprocess.PIPE
    )
    assert wait_child(sleeps, 1.0) == b""
    spins = subprocess.Popen([sys.executable, "-c", "while True: pass"], stderr=subprocess.PIPE)
    waits = subprocess.Popen(
        [sys.executable, "-c", f"import time; time.sleep({4 * WALL_FACTOR})"],
        stderr=subprocess.PIPE,
    )
    try:
        # (OVER unless the machine starves it first: its CPU time comes at the machine's pace)
        assert wait_child(spins, 1.0) in (OVER, STARVED)
        assert wait_child(waits, 0.5) == STARVED  # (Python's start-up: far less than 0.5 s CPU)
    finally:
        for child in (spins, waits):
            child.kill()
            child.communicate()


def test_a_lockstep_build_the_machine_starved_is_tried_again(
    numba, make_shader, own_cache, monkeypatch
):
    from glslcheck.backends.compiled_engine.budget import STARVED

    monkeypatch.delenv("GLSLCHECK_COMPILED_LANES", raising=False)
    shader = _shader(make_shader, "0.125 + 0.875")
    prog = engine.compile_compiled(shader)
    prog.render(size=SIZE, time=0.5)  # the per-pixel module, compiled here
    monkeypatch.setattr(engine, "wait_child", lambda child, seconds: STARVED)
    monkeypatch.setattr(engine.TieredProgram, "move_cost", lambda self: 0.0)
    assert prog.move_now() and prog.settle(600)
    assert prog.stay and prog.mode == "pixel" and not prog.over_budget()
    monkeypatch.undo()  # the real rule, the same cache
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(own_cache / "numba"))
    again = engine.compile_compiled(shader)
    assert not again.over_budget() and again.move_cost() < float("inf")
