"""File names never become options, and lint never writes over a shader it reads.

The pre-commit framework runs a hook as its `entry`, then its `args`, then the staged file names:
a file named `--output=Common.glsl` would be lint's --output unless the args end with `--`.
"""

from __future__ import annotations

import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
IMAGE = "void mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor = vec4(1.0); }\n"
COMMON = "float half_of(float x) { return x * 0.5; }\n"


def _hook_command() -> list[str]:
    """The hook definition's entry and args, as pre-commit puts them before the file names."""
    text = (ROOT / ".pre-commit-hooks.yaml").read_text()
    entry = re.search(r"^\s*entry:\s*(.+)$", text, re.M).group(1)
    args = re.search(r"^\s*args:\s*(\[.*\])\s*$", text, re.M)
    return shlex.split(entry) + (json.loads(args.group(1)) if args else [])


def test_a_staged_file_named_like_an_option_stays_a_file_name(tmp_path):
    (tmp_path / "Image.glsl").write_text(IMAGE)
    (tmp_path / "Common.glsl").write_text(COMMON)
    (tmp_path / "--output=Common.glsl").write_text(IMAGE)
    command = _hook_command()
    assert command[:2] == ["glslcheck", "lint"]
    argv = [sys.executable, "-m", "glslcheck", *command[1:], "--output=Common.glsl", "Image.glsl"]
    done = subprocess.run(argv, cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert done.returncode == 1, done.stderr  # findings in both files, reported on stdout
    assert "--output=Common.glsl:1:1" in done.stdout
    assert (tmp_path / "Common.glsl").read_text() == COMMON


def test_lint_refuses_to_write_its_report_over_a_tab_it_reads(tmp_path):
    (tmp_path / "Image.glsl").write_text(IMAGE)
    (tmp_path / "Common.glsl").write_text(COMMON)
    for output in ("Common.glsl", "Image.glsl"):
        done = subprocess.run(
            [sys.executable, "-m", "glslcheck", "lint", "Image.glsl", "-o", output],
            cwd=tmp_path,
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert done.returncode == 2
        assert done.stderr.startswith(f"{output}: error: --output names a shader file lint reads")
    assert (tmp_path / "Common.glsl").read_text() == COMMON and (
        tmp_path / "Image.glsl"
    ).read_text() == IMAGE
    done = subprocess.run(
        [sys.executable, "-m", "glslcheck", "lint", "Image.glsl", "-o", "report.txt"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 1 and "Image.glsl:1:1" in (tmp_path / "report.txt").read_text()
