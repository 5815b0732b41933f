"""The pre-commit hook on course repositories laid out as students lay them out.

Students keep each Shadertoy tab in a text file named as they like: the names below are those
of real GPR-200 repositories (the texts are ours: the lab's own part 1, Common and Image in one
file, as a student with one tab file has it). `glslcheck install-hook` is run and `git commit`
runs the hook for real: a shader with a finding must stop the commit whatever its name, a clean
one must go through, and a commit holding no shader file (a README, notes) goes through with a
note that nothing was linted and how to include other names, never a bare "no findings".

The hook runs the Python that installed it, isolated: so that it runs this checkout, the hook is
installed by a virtual environment whose path puts this checkout first (the packages come from
the running interpreter's site-packages).
"""

from __future__ import annotations

import re
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from .conftest import REPO_ROOT, GitRepo, snapshot

LAB_PART = REPO_ROOT / "lab_shaders" / "01_spheres_procedural"
COURSE_NAMES = [
    "Lab 4.txt",
    "Lab4/Lab4.txt",
    "code.txt",
    "shader.txt",
    "Shadertoy code.txt",
    "lab4_IanUrban.txt",
    "Lab04.txt",
    "GPRO-Graphics-Lab4/main.txt",
    "RLittleton_Lab4/RLittleton_Lab4_Text.txt",
]


def _body(path: Path) -> str:
    """A lab tab without its opening header block (the comment lines before the first blank)."""
    lines = path.read_text(encoding="utf-8").splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if not line.strip())
    return "".join(lines[start + 1 :])


def _one_file_shader(name: str, header: bool = True) -> str:
    """The lab's part 1 as one tab file named `name`: Common's code, then Image's."""
    top = (
        f"// {Path(name).name}: Lab 4 part 1, spheres drawn procedurally, normals as colours\n"
        "// Contributors: Ana Ruiz: the spheres and their normals; Ben Li: the comments\n"
        "// Starter framework by Daniel S. Buckstein, adapted.\n\n"
        if header
        else ""
    )
    return top + _body(LAB_PART / "Common.glsl") + "\n" + _body(LAB_PART / "Image.glsl")


@pytest.fixture(scope="module")
def hook_python(tmp_path_factory) -> str:
    """A Python that imports this checkout's glslcheck, also in isolated mode (`-I`): the running
    one when it does, else a virtual environment whose path puts this checkout first."""
    probe = [sys.executable, "-I", "-c", "import glslcheck; print(glslcheck.__file__)"]
    here = str(REPO_ROOT / "glslcheck" / "__init__.py")
    neutral = tmp_path_factory.mktemp("neutral")
    if subprocess.run(probe, capture_output=True, text=True, cwd=neutral).stdout.strip() == here:
        return sys.executable
    env_dir = tmp_path_factory.mktemp("venv")
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(env_dir)], check=True)
    python = env_dir / "bin" / "python"
    purelib = subprocess.run(
        [str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    # This checkout first, then the running interpreter's packages, then the import lines of
    # its .pth files (an editable install's finder supplies glslcheck.grammar from grammar/).
    packages = Path(sysconfig.get_paths()["purelib"])
    imports = [
        line
        for pth in sorted(packages.glob("*.pth"))
        for line in pth.read_text(encoding="utf-8").splitlines()
        if line.startswith("import")
    ]
    Path(purelib, "glslcheck-checkout.pth").write_text(
        "\n".join([str(REPO_ROOT), str(packages), *imports]) + "\n", encoding="utf-8"
    )
    return str(python)


def _install_hook(repo: GitRepo, python: str) -> None:
    proc = repo.run(python, "-m", "glslcheck", "install-hook")
    assert proc.returncode == 0, proc.stderr
    hook = (repo.root / ".git" / "hooks" / "pre-commit").read_text()
    assert f"PYTHON={python}" in hook and " -I -m glslcheck" in hook  # it runs this checkout


def _commit(repo: GitRepo, files: dict[str, str]) -> subprocess.CompletedProcess:
    paths = [repo.write(name, text) for name, text in files.items()]
    repo.git("add", "--", *files)
    before = snapshot(paths)
    proc = repo.git("commit", "-m", "lab 4", check=False)
    assert snapshot(paths) == before  # the hook modified nothing
    return proc


def _committed(repo: GitRepo, name: str) -> bool:
    return name in repo.git("ls-tree", "-r", "--name-only", "HEAD").stdout.splitlines()


@pytest.mark.parametrize("name", COURSE_NAMES)
def test_hook_lints_a_tab_file_of_any_name(git_repo: GitRepo, hook_python: str, name: str):
    _install_hook(git_repo, hook_python)
    notes = {"notes.txt": "We split the work: Ana did the spheres and Ben the comments.\n"}

    proc = _commit(git_repo, {name: _one_file_shader(name, header=False), **notes})
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0, out
    assert f"{name}:1:1: missing-header" in out
    assert re.search(r"\d+ findings? in 1 file\b", out), out  # notes.txt is not parsed as GLSL
    assert not _committed(git_repo, name)

    proc = _commit(git_repo, {name: _one_file_shader(name), **notes})
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "no findings in 1 file" in proc.stderr  # git shows a hook's output on stderr
    assert _committed(git_repo, name) and _committed(git_repo, "notes.txt")


def test_hook_says_when_it_linted_no_staged_file(git_repo: GitRepo, hook_python: str):
    _install_hook(git_repo, hook_python)
    proc = _commit(
        git_repo,
        {
            "notes.txt": "Lab 4 notes: the light sits above and to the right of the viewer.\n",
            "README.txt": "# Lab 4\n```glsl\nvoid mainImage(out vec4 c, in vec2 p) {}\n```\n",
            "LICENSE": "Creative Commons Attribution-NonCommercial-ShareAlike 3.0\n",
        },
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    note = proc.stderr  # git shows a hook's output on stderr
    assert "no findings" not in note
    assert "no shader files linted (0 files): nothing was checked" in note
    assert "no shader file linted; 3 staged files left out as not shader files" in note
    assert "LICENSE" in note and "notes.txt" in note and "README.txt" in note
    assert "tab-patterns" in note  # how to include other names
