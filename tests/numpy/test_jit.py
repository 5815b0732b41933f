"""When the compiled math kernels are used (backends/numpy_engine/jit.py): the modes, the tiered
rule of auto, numba's cache directory. Runs without numba: the kernels are replaced by a stand-in
that computes the reference and counts its calls (the real kernels are
tests/numpy/test_jit_kernels.py and test_jit_render.py)."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from glslcheck.backends.numpy_engine import jit
from glslcheck.backends.numpy_engine.llvmpipe_reference import LlvmpipeMath, blocked
from glslcheck.base.diagnostics import InputError

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
F32 = np.float32


class FakeKernels:
    """jit_kernels' interface, computing LlvmpipeMath's reference, counting calls."""

    def __init__(self) -> None:
        self.calls = 0
        self.lp = LlvmpipeMath(True)

    def trig(self, a, out, fma, which):
        self.calls += 1
        out[:] = getattr(self.lp, ("_sin", "_cos", "_tan")[which])(a)
        return True

    def explog(self, x, y, out, fma, which):
        self.calls += 1
        out[:] = (
            self.lp._pow(x, y) if which == 2 else getattr(self.lp, ("_exp2", "_log2")[which])(x)
        )
        return True


@pytest.fixture
def state(monkeypatch):
    """A fresh process state (numba "installed", not loaded); load() gives a FakeKernels."""
    fresh = jit._State()
    fresh.available = True
    monkeypatch.setattr(jit, "_STATE", fresh)
    fake = FakeKernels()
    loads = []

    def load(required=False):
        loads.append(fresh.spent)
        fresh.kernels = fake
        return fake

    monkeypatch.setattr(jit, "load", load)
    fresh.fake, fresh.loads = fake, loads
    return fresh


def test_off_returns_the_numpy_function_itself(state, monkeypatch):
    monkeypatch.setenv("GLSLCHECK_JIT", "off")
    run = LlvmpipeMath(True)._exp2
    assert jit.dispatch("_exp2", run, True) is run
    monkeypatch.setenv("GLSLCHECK_JIT", "auto")
    assert jit.dispatch("_polynomial", run, True) is run  # no kernel for it
    state.available = False
    assert jit.dispatch("_exp2", run, True) is run  # auto without numba: nothing changes


def test_a_bad_mode_is_an_input_error(monkeypatch):
    monkeypatch.setenv("GLSLCHECK_JIT", "fast")
    with pytest.raises(InputError, match="GLSLCHECK_JIT must be one of auto, on, off, not 'fast'"):
        jit.mode()


def test_on_without_numba_says_how_to_install_it(monkeypatch):
    fresh = jit._State()
    fresh.available = False
    monkeypatch.setattr(jit, "_STATE", fresh)
    monkeypatch.setenv("GLSLCHECK_JIT", "on")
    with pytest.raises(
        InputError, match=r"--jit on: numba is not installed \(pip install 'glslcheck\[jit\]'\)"
    ):
        jit.dispatch("_sin", LlvmpipeMath(True)._sin, True)


def test_on_uses_the_kernels_from_the_first_call(state, monkeypatch):
    monkeypatch.setenv("GLSLCHECK_JIT", "on")
    lp = LlvmpipeMath(True)
    x = np.linspace(-3, 3, 100, dtype=F32)
    assert np.array_equal(lp.sin_or_cos(x, cos=False), blocked(lp._sin, x))
    assert state.fake.calls == 1 and state.loads == [0.0]


def test_auto_loads_once_small_calls_have_cost_the_load(state, monkeypatch):
    """Calls are timed on NumPy until their time exceeds the threshold (the last load's time);
    then the kernels are loaded and every later call, of every function and LlvmpipeMath made
    before or after, takes them. Calls of a dtype other than float32 stay on NumPy."""
    monkeypatch.setenv("GLSLCHECK_JIT", "auto")
    state.threshold = 0.05
    lp = LlvmpipeMath(True)
    small = np.linspace(0.1, 3, 143, dtype=F32)
    while not state.loads:
        assert np.array_equal(lp.exp2(small), blocked(lp._exp2, small))
    assert state.loads[0] > 0.05 and state.fake.calls == 0  # the call that crossed ran on NumPy
    lp.exp2(small)
    LlvmpipeMath(False).pow(small, small)
    lp.exp2(np.linspace(0.1, 3, 50_000, dtype=F32))
    lp.exp2(small.astype(np.float64))
    assert state.fake.calls == 3 and len(state.loads) == 1


def test_threshold_is_the_recorded_load_time_of_this_cache(state, monkeypatch, tmp_path):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(jit, "_stamp", lambda: ["0.68.1", 1, 2])
    assert jit.threshold() == jit.COLD_SECONDS  # no record yet
    (tmp_path / "glslcheck-jit.json").write_text(
        json.dumps({"seconds": 1.25, "stamp": ["0.68.1", 1, 2]})
    )
    state.threshold = None
    assert jit.threshold() == 1.25
    (tmp_path / "glslcheck-jit.json").write_text(
        json.dumps({"seconds": 1.25, "stamp": ["0.69.0", 1, 2]})
    )
    state.threshold = None
    assert jit.threshold() == jit.COLD_SECONDS  # another numba or kernels source: compiles anew


def test_numba_cache_goes_to_the_user_cache(monkeypatch, tmp_path):
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert jit.cache_dir() == os.path.join(str(tmp_path), "glslcheck", "numba")
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert jit.cache_dir() == os.path.join(str(tmp_path), "home", ".cache", "glslcheck", "numba")
    monkeypatch.setenv("NUMBA_CACHE_DIR", "/elsewhere")  # the user's own choice wins
    assert jit.cache_dir() == "/elsewhere"


KEEPS_CONFIG = """
import numba
from numba.core import config
config.SLP_VECTORIZE = 1  # as the lockstep engine sets it before compiling a module
from glslcheck.backends.numpy_engine import jit
print(jit.use_cache_dir())
numba.njit(lambda x: x + 1)(1)  # a compile: numba reloads its config if the environment changed
print(config.SLP_VECTORIZE, config.CACHE_DIR)
"""


def test_setting_the_cache_dir_keeps_numbas_other_settings(numba, tmp_path):
    """numba imported first, a setting assigned, then the cache directory set: a compile after
    that reloads nothing, so the setting holds (with ``os.environ.setdefault`` alone the compile
    re-read numba's config from the environment and SLP_VECTORIZE was 0 again)."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env["XDG_CACHE_HOME"] = str(tmp_path)
    done = subprocess.run(
        [sys.executable, "-c", KEEPS_CONFIG], capture_output=True, text=True, env=env, timeout=120
    )
    assert done.returncode == 0, done.stderr
    path, after = done.stdout.splitlines()
    assert path == os.path.join(str(tmp_path), "glslcheck", "numba")
    assert after == f"1 {path}"


def test_cli_rejects_a_bad_glslcheck_jit(tmp_path):
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "glslcheck",
            "render",
            os.path.join(ROOT, "lab_shaders", "07_final"),
            "-o",
            str(tmp_path / "x.png"),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=dict(os.environ, GLSLCHECK_JIT="fast"),
        timeout=120,
    )
    assert done.returncode == 2 and not (tmp_path / "x.png").exists()
    assert (
        done.stderr.strip()
        == "glslcheck: error: GLSLCHECK_JIT must be one of auto, on, off, not 'fast'"
    )


def test_after_a_compile_the_threshold_is_a_load_from_the_cache(state, monkeypatch, tmp_path):
    """A load that compiled the kernels records so: the next process waits for numba's import
    time plus WARM_KERNELS_SECONDS of math, not for the compile; a record of a load from the
    cache is taken as it is."""
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(jit, "_stamp", lambda: ["0.68.1", 1, 2])
    record = {"seconds": 9.5, "stamp": ["0.68.1", 1, 2], "compiled": True, "numba": 0.75}
    (tmp_path / "glslcheck-jit.json").write_text(json.dumps(record))
    assert jit.threshold() == 0.75 + jit.WARM_KERNELS_SECONDS
    (tmp_path / "glslcheck-jit.json").write_text(json.dumps(dict(record, compiled=False)))
    state.threshold = None
    assert jit.threshold() == 9.5


def test_workers_counts_decide_for_all_of_them(state, monkeypatch):
    """A render worker reports what it counted since its last frame (counted); the parent adds
    the reports up (add_counted) and decides once they exceed the threshold times the number of
    workers; then the parent, if it renders itself, loads at its first call, without counting."""
    monkeypatch.setenv("GLSLCHECK_JIT", "auto")
    state.threshold = 1.0
    state.spent = 0.25
    assert jit.counted() == 0.25 and jit.counted() == 0.0
    state.spent = 0.5
    assert jit.counted() == 0.25
    jit.add_counted(1.5, 2)
    assert not jit.decided()
    jit.add_counted(0.75, 2)  # 2.25 > 1.0 * 2
    assert jit.decided() and not state.loads
    lp = LlvmpipeMath(True)
    small = np.linspace(0.1, 3, 143, dtype=F32)
    assert np.array_equal(lp.exp2(small), blocked(lp._exp2, small))
    assert (
        state.loads == [0.5] and state.fake.calls == 1
    )  # loaded before the first call, which took them
    monkeypatch.setenv("GLSLCHECK_JIT", "off")
    fresh = jit._State()
    monkeypatch.setattr(jit, "_STATE", fresh)
    fresh.threshold = 1.0
    jit.add_counted(5.0, 1)
    assert not jit.decided()  # off never decides
