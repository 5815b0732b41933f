"""The grammar and its parser tables ship inside the wheel: an installed (non-editable)
glslcheck finds them."""

from __future__ import annotations

import os
import subprocess
import sys
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_wheel_contains_grammar_and_parses_from_it(tmp_path):
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", str(tmp_path), str(ROOT)],
        check=True,
        capture_output=True,
    )
    (wheel,) = tmp_path.glob("glslcheck-*.whl")
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        assert "glslcheck/grammar/glsl.lark" in names
        assert "glslcheck/grammar/glsl_tables.json" in names  # the parser's tables (parse_tables.py)
        z.extractall(tmp_path / "site")
    # Run from an unrelated folder with only the unpacked wheel on the path: the source tree's
    # grammar/ folder is not reachable, so the grammar must come from the package data.
    code = (
        "import glslcheck.parse as p, sys; "
        "assert 'site' in p.__file__, p.__file__; "
        "t = p.parse_string('void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }'); "
        "print(type(t).__name__)"
    )
    env = dict(os.environ, PYTHONPATH=str(tmp_path / "site"), XDG_CACHE_HOME=str(tmp_path / "cache"))
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "TranslationUnit"
    assert out.stderr == ""  # the shipped tables match the shipped grammar: nothing rebuilt
