"""Start-up: `glslcheck lint`, `check` and `parse` run in every pre-commit hook, so
they must not import what only rendering needs (NumPy, moderngl, Pillow) nor Lark (the parser's
tables ship as data, glslcheck/frontend/parse_tables.py). Deterministic: a fresh interpreter runs
the command and reports which modules it loaded; no timing is asserted (see
benchmarks/bench_startup.py for the times)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
# dataclasses: its per-class code generation cost a one-file lint about 40 M instructions; the
# start-up path uses glslcheck.base.records.
HEAVY = (
    "numpy",
    "moderngl",
    "PIL",
    "lark",
    "multiprocessing",
    "concurrent",
    "dataclasses",
    "numba",
    "llvmlite",
)

_RUN = """
import io, json, sys, contextlib
preloaded = sorted(sys.modules)  # by the interpreter and site (an editable install's finder)
from glslcheck.cli.main import main
out = io.StringIO()
with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
    code = main(sys.argv[1:])
print(json.dumps({"code": code, "modules": sorted(sys.modules), "preloaded": preloaded}))
"""


@pytest.mark.parametrize("command", [["lint"], ["check"], ["parse"], ["lint", "--format", "json"]])
def test_lint_check_and_parse_load_no_renderer_and_no_lark(command):
    shader = ROOT / "lab_shaders" / "07_final"
    done = subprocess.run(
        [sys.executable, "-c", _RUN, command[0], str(shader), *command[1:]],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout.strip().splitlines()[-1])
    assert report["code"] in (0, 1)
    loaded = {m.split(".")[0] for m in report["modules"]}
    assert "glslcheck.frontend.parser" in report["modules"]  # the command did its work
    assert not loaded & set(HEAVY), sorted(loaded & set(HEAVY))


def test_lint_does_not_import_typing(tmp_path):
    """`typing` is a few milliseconds of every start-up: the lint path names its types under
    `if TYPE_CHECKING:` only. (Run outside this repository: its pyproject.toml is read with
    tomllib, which imports typing itself.)"""
    import shutil

    shader = tmp_path / "shader"
    shutil.copytree(ROOT / "lab_shaders" / "07_final", shader)
    done = subprocess.run(
        [sys.executable, "-c", _RUN, "lint", str(shader)],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout.strip().splitlines()[-1])
    assert "glslcheck.lint.rules.repeated_expression" in report["modules"]  # the rules ran
    assert "typing" not in report["modules"]
    # pathlib (with urllib.parse and ipaddress): about 17 M instructions; the lint path spells
    # its paths with glslcheck.shadertoy.sources' helpers (tests/test_sources.py holds them to
    # pathlib's). (The dev venv's editable-install finder imports pathlib in `site`, before
    # glslcheck.)
    loaded = {m.split(".")[0] for m in set(report["modules"]) - set(report["preloaded"])}
    assert not {"pathlib", "urllib", "difflib"} & loaded


def test_check_expands_only_the_builtin_functions_it_looks_up():
    """builtins.BUILTINS keeps the spec's generic signatures and expands a function's overloads
    on its first look-up (expanding all of them at import was a sixth of a one-file lint)."""
    code = (
        "import io, contextlib, sys; from glslcheck.cli.main import main; "
        "from glslcheck.language import builtin_functions as B\n"
        "with contextlib.redirect_stdout(io.StringIO()): main(sys.argv[1:])\n"
        "print(len(B.BUILTINS._built), len(B.BUILTINS), 'texture' in B.BUILTINS._built)"
    )
    done = subprocess.run(
        [sys.executable, "-c", code, "check", str(ROOT / "lab_shaders" / "07_final")],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    built, total, texture = done.stdout.split()
    assert 0 < int(built) < int(total) == 89 and texture == "False"


@pytest.mark.parametrize("jit", ["auto", "off"])
def test_a_cheap_render_never_loads_numba(tmp_path, jit):
    """numba (the optional `jit` extra, backends/numpy_engine/jit.py) costs 0.7-2 s to load: a
    render that spends less than that in the llvmpipe math on few lanes (a lab scene) must not load
    it in auto mode, and --jit off never does. (Installed or not, this holds; on a machine without
    numba it holds trivially.)"""
    done = subprocess.run(
        [
            sys.executable,
            "-c",
            _RUN,
            "render",
            str(ROOT / "lab_shaders" / "07_final"),
            "--size",
            "200x112",
            "--parallel",
            "threads",
            "--jit",
            jit,
            "-o",
            str(tmp_path / "out.png"),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout.strip().splitlines()[-1])
    assert report["code"] == 0 and (tmp_path / "out.png").exists()
    assert (
        "glslcheck.backends.numpy_engine.runtime" in report["modules"]
    )  # the NumPy backend rendered
    assert not {m.split(".")[0] for m in report["modules"]} & {"numba", "llvmlite"}
