"""Each shape of the fuzzer's hostile programs (deep nesting, long chains, huge arrays,
runaway loops) at its largest, through check, transpile and render in-process: check accepts it,
transpile and render end ok or with an error located in the file (the frame budget,
fuzz.FRAME_SECONDS, stops the runaway loops), never a traceback. The long run is
`python tools/fuzz.py --hostile-rate 1.0 --count N` (see tools/fuzz.py)."""

from __future__ import annotations

import importlib
import random
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _fuzz_module():
    tools = str(ROOT / "tools")
    if tools not in sys.path:
        sys.path.insert(0, tools)
    return importlib.import_module("fuzz")


fuzz = _fuzz_module()


class _Largest(random.Random):
    """Picks the last (largest) option of every choice, so each shape runs at its limit."""

    def choice(self, seq):
        return seq[-1]


@pytest.fixture(scope="module")
def worker():
    """The fuzzer's own worker process (spawned; 3 GB address-space limit, CPU-time budgets),
    so the arrays of these renders never grow the test process."""
    import multiprocessing as mp

    w = fuzz.Worker(mp.get_context("spawn"))
    yield w
    w.close()


@pytest.mark.parametrize("shape", fuzz.HOSTILE_SHAPES)
def test_hostile_shape_at_its_largest(worker, shape):
    text = fuzz.hostile_program(_Largest(16), shape)
    data = {"shader.glsl": text.encode()}
    outcomes = {c: worker.run(c, data, fuzz.BUDGET[c]) for c in ("check", "transpile", "render")}
    assert outcomes["check"][0] == "ok", outcomes["check"]
    for command in ("transpile", "render"):
        assert outcomes[command][0] in ("ok", "findings"), (command, outcomes[command])
    if shape != "runaway":  # the others finish well inside the budget
        assert outcomes["render"][0] == "ok", outcomes["render"]
