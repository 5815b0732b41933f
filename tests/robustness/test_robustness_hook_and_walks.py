"""The folder walk under unlucky trees: check, lint, parse and report must enter each real folder
once, whatever symbolic links point back up the tree.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from test_security_hook import CLEAN

CHECKOUT = str(Path(__file__).resolve().parents[2])  # the glslcheck these tests run


def _glslcheck(*args: str, cwd: Path, env: dict | None = None) -> subprocess.CompletedProcess:
    env = {**(os.environ if env is None else env), "PYTHONPATH": CHECKOUT}
    return subprocess.run([sys.executable, "-m", "glslcheck", *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=60)


# Folders holding symbolic links to themselves or above ------------------------------------------


def _looping_tree(root: Path, outside: Path) -> None:
    (root / "lab1").mkdir(parents=True)
    (root / "lab1" / "Image.glsl").write_text(CLEAN, encoding="utf-8")
    (root / "notes" / "deeper").mkdir(parents=True)
    (root / "notes" / "loose.glsl").write_text(CLEAN, encoding="utf-8")
    for link, target in (("again", "."), ("self", "."), ("notes/up", ".."), ("notes/deeper/top", "../.."),
                         ("notes/deeper/here", "."), ("notes/absolute", str(root)), ("shared", str(outside))):
        os.symlink(target, root / link)
    (outside / "lab9").mkdir(parents=True)
    (outside / "lab9" / "Image.glsl").write_text(CLEAN, encoding="utf-8")
    os.symlink("..", outside / "lab9" / "back")


# Every shader of the looping tree once, under its own name; a link out of the tree (shared) is
# still followed. lint lints only files inside the folder it is given, so not shared/lab9.
SHADERS = ["course/lab1", "course/notes/loose.glsl", "course/shared/lab9"]


def test_walk_enters_each_real_folder_once(tmp_path: Path):
    _looping_tree(tmp_path / "course", tmp_path / "outside")
    code = "from glslcheck.shadertoy.sources import find_shaders\nfor s in find_shaders(['course']): print(s.root)\n"
    proc = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=60,
                          env={**os.environ, "PYTHONPATH": CHECKOUT})
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines() == SHADERS


@pytest.mark.parametrize("command, summary", [
    (["lint"], f"no findings in {len(SHADERS) - 1} files"),
    (["check"], f"checked {len(SHADERS)} programs: {len(SHADERS)} clean"),
    (["parse"], f"parsed {len(SHADERS)} of {len(SHADERS)} programs"),
    (["report", "--no-webgl", "--no-bench", "--size", "8x8", "-o", "report.html"],
     f"{len(SHADERS)} shaders, all clean"),
])
def test_commands_walk_a_folder_that_links_to_itself(tmp_path: Path, command: list[str], summary: str):
    _looping_tree(tmp_path / "course", tmp_path / "outside")
    proc = _glslcheck(command[0], "course", *command[1:], cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert summary in proc.stdout + proc.stderr
