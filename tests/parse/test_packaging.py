"""The grammar and its parser tables ship inside the wheel: an installed (non-editable)
glslcheck finds them."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_wheel_contains_grammar_and_parses_from_it(tmp_path):
    # Built from a copy of what the wheel is made of: setuptools builds through the source
    # folder's build/, whose files from an earlier build would otherwise ship too.
    src = tmp_path / "src"
    for name in ("glslcheck", "grammar"):
        shutil.copytree(ROOT / name, src / name, ignore=shutil.ignore_patterns("__pycache__"))
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, src / name)
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "--no-build-isolation",
            "-q",
            "-w",
            str(tmp_path),
            str(src),
        ],
        check=True,
        capture_output=True,
    )
    (wheel,) = tmp_path.glob("glslcheck-*.whl")
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        assert "glslcheck/grammar/glsl.lark" in names
        assert (
            "glslcheck/grammar/glsl_tables.py" in names
        )  # the parser's tables (frontend/parse_tables.py)
        z.extractall(tmp_path / "site")
    # Run from an unrelated folder with only the unpacked wheel on the path: the source tree's
    # grammar/ folder is not reachable, so the grammar must come from the package data.
    code = (
        "import glslcheck.frontend.parser as p, sys; "
        "assert 'site' in p.__file__, p.__file__; "
        "t = p.parse_string('void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }'); "
        "print(type(t).__name__)"
    )
    env = dict(
        os.environ, PYTHONPATH=str(tmp_path / "site"), XDG_CACHE_HOME=str(tmp_path / "cache")
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "TranslationUnit"
    assert out.stderr == ""  # the shipped tables match the shipped grammar: nothing rebuilt
    # Every package of the source tree ships (a missing one, glslcheck.semantics.analysis, made the
    # installed `glslcheck lint` fail at its first AST rule), and the installed command lints.
    packages = {str(p.parent.relative_to(ROOT)) for p in (ROOT / "glslcheck").rglob("__init__.py")}
    missing = sorted(p for p in packages if f"{p}/__init__.py" not in names)
    assert not missing, (
        f"packages left out of the wheel (pyproject.toml [tool.setuptools] packages): {missing}"
    )
    lab_file = ROOT / "lab_shaders" / "07_final" / "Image.glsl"
    lint = subprocess.run(
        [
            sys.executable,
            "-c",
            "import sys; from glslcheck.cli.main import main; sys.exit(main())",
            "lint",
            str(lab_file),
        ],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
    )
    assert lint.returncode in (0, 1) and "Traceback" not in lint.stderr, lint.stderr
    assert "file" in lint.stdout
    # The pytest plugin comes with the wheel: a fresh project's test asks for the fixture by
    # name, with no -p and no conftest (the entry point in the wheel's metadata loads it).
    (tmp_path / "project").mkdir()
    (tmp_path / "project" / "test_shader.py").write_text(
        "def test_the_final_part_is_finite(shader_check):\n"
        "    shader_check.assert_no_nan("
        f"{str(ROOT / 'lab_shaders' / '07_final')!r}, size=(32, 18))\n"
    )
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "test_shader.py"],
        cwd=tmp_path / "project",
        env=env,
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0 and "1 passed" in run.stdout, run.stdout + run.stderr
    with zipfile.ZipFile(wheel) as z:
        (entry_points,) = [n for n in names if n.endswith(".dist-info/entry_points.txt")]
        assert "[pytest11]\nglslcheck.testing = glslcheck.testing" in z.read(entry_points).decode()
