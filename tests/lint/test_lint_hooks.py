"""Git hooks, run for real in a temporary repository: the pre-commit framework with a local
hook configured like .pre-commit-hooks.yaml's, and the plain hook `glslcheck install-hook`
writes. A commit with findings is refused, a clean one goes through, and no file is modified."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import yaml

from glslcheck.cli.commands.install_hook import MARKER

from .conftest import BAD_SHADER, CLEAN_SHADER, REPO_ROOT, GitRepo, snapshot

HOOKS_YAML = REPO_ROOT / ".pre-commit-hooks.yaml"
GLSLCHECK = f"{shlex.quote(sys.executable)} -m glslcheck"


def _hook_definition() -> dict:
    hooks = yaml.safe_load(HOOKS_YAML.read_text())
    return next(h for h in hooks if h["id"] == "glslcheck-lint")


def test_hook_definition():
    hook = _hook_definition()
    # pre-commit passes every .txt and extension-less file; glslcheck keeps those whose text is
    # a shader's (a student's `Lab 4.txt`) and passes over a README or notes file
    assert hook["entry"] == "glslcheck lint --skip-non-shaders"
    assert hook["language"] == "python"
    assert hook["pass_filenames"] is True
    assert hook["types"] == ["text"]
    files = re.compile(hook["files"])
    for name in (
        "Image.glsl",
        "lab4/shade.frag",
        "lab4/Buffer A.txt",
        "lab4/buffer_b",
        "Common",
        "x/IMAGE.TXT",
        "Lab 4.txt",
        "GPRO-Graphics-Lab4/main.txt",
        "notes.txt",
    ):
        assert files.search(name), name
    for name in ("README.md", "lab4/image.png", "src/main.cpp", ".gitignore"):
        assert not files.search(name), name


def _commit(repo: GitRepo, name: str, text: str) -> tuple[subprocess.CompletedProcess, Path]:
    path = repo.write(name, text)
    repo.git("add", name)
    before = snapshot([path])
    proc = repo.git("commit", "-m", f"add {name}", check=False)
    assert snapshot([path]) == before  # the hook modified nothing
    return proc, path


def _committed(repo: GitRepo, name: str) -> bool:
    return name in repo.git("ls-tree", "-r", "--name-only", "HEAD").stdout.splitlines()


def test_pre_commit_framework_runs_the_hook(git_repo: GitRepo):
    hook = _hook_definition()
    config = {
        "repos": [
            {
                "repo": "local",
                "hooks": [
                    {
                        "id": hook["id"],
                        "name": hook["name"],
                        "entry": f"{GLSLCHECK} lint --skip-non-shaders",
                        "language": "system",
                        "files": hook["files"],
                        "pass_filenames": hook["pass_filenames"],
                    }
                ],
            }
        ]
    }
    git_repo.write(".pre-commit-config.yaml", yaml.safe_dump(config))
    git_repo.git("add", ".pre-commit-config.yaml")
    git_repo.git("commit", "-q", "-m", "pre-commit config")
    git_repo.run(sys.executable, "-m", "pre_commit", "install")

    proc, _ = _commit(git_repo, "lab4/Image.glsl", BAD_SHADER)
    assert proc.returncode != 0
    assert "missing-comment" in proc.stdout + proc.stderr
    assert not _committed(git_repo, "lab4/Image.glsl")

    proc, _ = _commit(git_repo, "lab4/Image.glsl", CLEAN_SHADER)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert _committed(git_repo, "lab4/Image.glsl")

    proc, _ = _commit(git_repo, "notes.txt", "not a shader\n")  # not a shader: the hook skips it
    assert proc.returncode == 0, proc.stdout + proc.stderr

    # a tab file named as a student names it: a shader by its text
    proc, _ = _commit(git_repo, "Lab4/Lab4.txt", BAD_SHADER)
    assert proc.returncode != 0
    assert "Lab4/Lab4.txt:1:1: missing-header" in proc.stdout + proc.stderr
    assert not _committed(git_repo, "Lab4/Lab4.txt")


def test_install_hook_blocks_findings_and_passes_clean(git_repo: GitRepo):
    proc = git_repo.run(sys.executable, "-m", "glslcheck", "install-hook")
    assert proc.returncode == 0, proc.stderr
    hook = git_repo.root / ".git" / "hooks" / "pre-commit"
    assert MARKER in hook.read_text() and hook.stat().st_mode & 0o111

    proc, _ = _commit(git_repo, "lab4/Buffer A.glsl", BAD_SHADER)
    assert proc.returncode != 0
    assert "lab4/Buffer A.glsl:1:1: missing-header" in proc.stdout + proc.stderr
    assert not _committed(git_repo, "lab4/Buffer A.glsl")
    git_repo.git("rm", "-q", "--cached", "lab4/Buffer A.glsl")  # the student leaves it out

    proc, _ = _commit(git_repo, "lab4/Image.glsl", CLEAN_SHADER)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert _committed(git_repo, "lab4/Image.glsl")

    proc, _ = _commit(git_repo, "notes.txt", "not a shader\n")
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_install_hook_is_posix_sh(git_repo: GitRepo):
    git_repo.run(sys.executable, "-m", "glslcheck", "install-hook")
    hook = git_repo.root / ".git" / "hooks" / "pre-commit"
    assert hook.read_text().startswith("#!/bin/sh\n")
    assert subprocess.run(["sh", "-n", str(hook)]).returncode == 0


def test_install_hook_refuses_foreign_hook(git_repo: GitRepo):
    hook = git_repo.root / ".git" / "hooks" / "pre-commit"
    hook.write_text("#!/bin/sh\necho mine\n")
    proc = git_repo.run(sys.executable, "-m", "glslcheck", "install-hook", check=False)
    assert proc.returncode == 2 and "--force" in proc.stderr
    assert hook.read_text() == "#!/bin/sh\necho mine\n"

    proc = git_repo.run(sys.executable, "-m", "glslcheck", "install-hook", "--force")
    assert proc.returncode == 0 and "replaced" in proc.stdout
    assert MARKER in hook.read_text()
    assert (hook.parent / "pre-commit.glslcheck-backup").read_text() == "#!/bin/sh\necho mine\n"

    proc = git_repo.run(sys.executable, "-m", "glslcheck", "install-hook")  # its own hook: updated
    assert proc.returncode == 0 and "updated" in proc.stdout


def test_install_hook_outside_a_repository(tmp_path):
    from .conftest import git_env

    (tmp_path / "home").mkdir()
    proc = subprocess.run(
        [sys.executable, "-m", "glslcheck", "install-hook"],
        cwd=tmp_path,
        env=git_env(tmp_path / "home"),
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    assert "not inside a git repository" in proc.stderr and "Traceback" not in proc.stderr


FIXABLE_SHADER = CLEAN_SHADER.replace(
    "    fragColor = vec4(0.2, 0.4, 0.6, 1.0);\n",
    "    float d = length(fragCoord); // distance from the corner\n"
    "    fragColor = vec4(vec3(pow(d, 2.0)), 1.0); // its square\n",
)


def test_the_hook_names_the_command_that_fixes_and_rewrites_nothing(
    git_repo: GitRepo, monkeypatch, capsys
):
    """`lint --staged`, the hook's command, run in this process (the hook itself runs the
    installed glslcheck in isolated mode)."""
    from glslcheck.cli.main import main

    path = git_repo.write("lab4/Image.glsl", FIXABLE_SHADER)
    git_repo.git("add", "lab4/Image.glsl")
    before = snapshot([path])
    monkeypatch.chdir(git_repo.root)
    for key, value in git_repo.env.items():
        monkeypatch.setenv(key, value)
    assert main(["lint", "--staged"]) == 1
    out = capsys.readouterr().out
    assert "pow-small-exponent" in out
    assert "`glslcheck lint --fix lab4/Image.glsl` applies" in out
    assert snapshot([path]) == before  # neither the work tree nor the index changed
    assert git_repo.git("show", ":lab4/Image.glsl").stdout == FIXABLE_SHADER
