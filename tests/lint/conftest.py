"""Shared helpers of the lint tests: fixture paths, a git repository in a temp folder."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
FIXTURES = HERE / "fixtures"
REPO_ROOT = HERE.parent.parent

# A shader every rule accepts (the hooks must let it through).
CLEAN_SHADER = """\
// Image.glsl: paints the screen one colour (a clean shader for the hook tests)
// Contributors: Ana Ruiz: the colour; Ben Li: the comments
// Starter framework by Daniel S. Buckstein.

// write a constant colour to every pixel
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.2, 0.4, 0.6, 1.0);
}
"""

# A shader with findings: no header, no comments.
BAD_SHADER = """\
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(1.0);
}
"""


def git_env(home: Path) -> dict[str, str]:
    """An environment where git and pre-commit see no user or system configuration."""
    env = dict(os.environ)
    env.update(
        HOME=str(home),
        GIT_CONFIG_GLOBAL=os.devnull,
        GIT_CONFIG_NOSYSTEM="1",
        GIT_AUTHOR_NAME="Test",
        GIT_AUTHOR_EMAIL="test@example.com",
        GIT_COMMITTER_NAME="Test",
        GIT_COMMITTER_EMAIL="test@example.com",
        GIT_CEILING_DIRECTORIES=str(home.parent),
        PRE_COMMIT_HOME=str(home / ".pre-commit-cache"),
    )
    for key in ("GIT_DIR", "GIT_WORK_TREE", "GIT_INDEX_FILE"):
        env.pop(key, None)
    return env


class GitRepo:
    def __init__(self, root: Path, env: dict[str, str]):
        self.root, self.env = root, env

    def run(self, *args: str, check: bool = True) -> subprocess.CompletedProcess:
        return subprocess.run(
            args, cwd=self.root, env=self.env, capture_output=True, text=True, check=check
        )

    def git(self, *args: str, check: bool = True) -> subprocess.CompletedProcess:
        return self.run("git", *args, check=check)

    def write(self, name: str, text: str) -> Path:
        p = self.root / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
        return p


@pytest.fixture
def git_repo(tmp_path: Path) -> GitRepo:
    home = tmp_path / "home"
    home.mkdir()
    root = tmp_path / "repo"
    root.mkdir()
    repo = GitRepo(root, git_env(home))
    repo.git("init", "-q", "-b", "main")
    repo.write("README.md", "a course repository\n")
    repo.git("add", "README.md")
    repo.git("commit", "-q", "-m", "start")
    return repo


def snapshot(paths: list[Path]) -> dict[Path, tuple[bytes, int]]:
    """Bytes and modification time of each file, to prove that nothing was written."""
    return {p: (p.read_bytes(), p.stat().st_mtime_ns) for p in paths}
