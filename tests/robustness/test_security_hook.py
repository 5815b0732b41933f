"""Security and correctness of the pre-commit hook `glslcheck install-hook` writes.

Run for real: a temporary git repository, the hook installed, `git commit` run. The hook must
run the installed glslcheck, never a `glslcheck/` folder of the repository (that would run the
repository's code on every commit), and must lint what the commit holds (the staged index), not
the work tree, including renamed-and-edited files and names git would quote.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

CLEAN = """\
// Image.glsl: one flat teal colour over the whole screen (passes every lint rule)
// Contributors: Mia Chen: the shader; Omar Haddad: its comments
// Starter framework by Daniel S. Buckstein.

// every pixel gets the same teal
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.1, 0.5, 0.5, 1.0);
}
"""
# No header and no comments: the linter reports missing-header at 1:1.
BAD = "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n    fragColor = vec4(1.0);\n}\n"


class Repo:
    def __init__(self, root: Path):
        self.root = root
        home = root.parent / "home"
        home.mkdir(exist_ok=True)
        env = {k: v for k, v in os.environ.items() if not k.startswith("GIT_")}
        env.update(
            {
                "HOME": str(home),
                "GIT_CONFIG_GLOBAL": os.devnull,
                "GIT_CONFIG_NOSYSTEM": "1",
                "GIT_CEILING_DIRECTORIES": str(root.parent),
            }
        )
        for role in ("AUTHOR", "COMMITTER"):
            env[f"GIT_{role}_NAME"], env[f"GIT_{role}_EMAIL"] = "Test", "test@example.com"
        self.env = env

    def git(self, *args: str, check: bool = True) -> subprocess.CompletedProcess:
        return subprocess.run(
            ["git", *args], cwd=self.root, env=self.env, capture_output=True, text=True, check=check
        )

    def write(self, name: str, text: str) -> Path:
        path = self.root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        return path

    def commit(self, message: str = "change") -> subprocess.CompletedProcess:
        return self.git("commit", "-m", message, check=False)

    def committed(self) -> list[str]:
        return self.git("ls-tree", "-r", "-z", "--name-only", "HEAD").stdout.split("\0")


def new_repo(tmp_path: Path) -> Repo:
    """A course repository with one commit, in tmp_path/repo."""
    root = tmp_path / "repo"
    root.mkdir()
    r = Repo(root)
    r.git("init", "-q", "-b", "main")
    r.write("README.md", "a course repository\n")
    r.git("add", "README.md")
    r.git("commit", "-q", "-m", "start")
    return r


@pytest.fixture
def repo(tmp_path: Path) -> Repo:
    r = new_repo(tmp_path)
    root = r.root
    proc = subprocess.run(
        [sys.executable, "-m", "glslcheck", "install-hook"],
        cwd=root,
        env=r.env,
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, proc.stderr
    return r


def test_security_hook_never_imports_a_glslcheck_folder_of_the_repository(
    repo: Repo, tmp_path: Path
):
    marker = tmp_path / "repository-code-ran"
    payload = f"open({str(marker)!r}, 'w').write('ran')\n"
    repo.write("glslcheck/__init__.py", payload)
    repo.write("glslcheck/__main__.py", payload)
    repo.write("glslcheck/cli/main.py", payload + "def main():\n    return 0\n")
    repo.git("add", "glslcheck")
    assert repo.commit("a package named like the tool").returncode == 0
    repo.write("lab4/Image.glsl", BAD)
    repo.git("add", "lab4/Image.glsl")
    proc = repo.commit()
    assert not marker.exists(), "the hook ran code from the repository"
    assert proc.returncode != 0  # the installed glslcheck ran and found the bad shader
    assert "lab4/Image.glsl:1:1: missing-header" in proc.stdout + proc.stderr


def test_security_hook_with_a_shader_folder_named_glslcheck(repo: Repo):
    repo.write("glslcheck/Image.glsl", CLEAN)
    repo.git("add", "glslcheck/Image.glsl")
    proc = repo.commit()
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr


def test_security_hook_runs_python_isolated(repo: Repo):
    text = (repo.root / ".git" / "hooks" / "pre-commit").read_text()
    assert " -I -m glslcheck lint --staged" in text or " -E -P -m glslcheck lint --staged" in text
    assert (
        subprocess.run(["sh", "-n", str(repo.root / ".git" / "hooks" / "pre-commit")]).returncode
        == 0
    )


def test_hook_lints_the_staged_version_not_the_work_tree(repo: Repo):
    path = repo.write("lab4/Image.glsl", BAD)
    repo.git("add", "lab4/Image.glsl")
    path.write_text(CLEAN, encoding="utf-8")  # a clean working copy over a bad staged version
    proc = repo.commit()
    assert proc.returncode != 0
    out = proc.stdout + proc.stderr
    assert "lab4/Image.glsl:1:1: missing-header" in out  # the user's path, not a temporary one
    assert "glslcheck-staged" not in out
    assert path.read_text(encoding="utf-8") == CLEAN  # the work tree is left alone

    repo.git("add", "lab4/Image.glsl")
    path.write_text(BAD, encoding="utf-8")  # now a bad working copy over a clean staged version
    proc = repo.commit()
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert repo.git("show", "HEAD:lab4/Image.glsl").stdout == CLEAN
    assert path.read_text(encoding="utf-8") == BAD


def test_hook_lints_a_renamed_and_edited_file(repo: Repo):
    long_clean = CLEAN + "".join(
        f"// line {i} of padding so the rename is detected\n" for i in range(20)
    )
    repo.write("lab4/Image.glsl", long_clean)
    repo.git("add", "lab4/Image.glsl")
    assert repo.commit().returncode == 0
    repo.git("mv", "lab4/Image.glsl", "lab4/Final.glsl")
    # Edited after the move: the header's first line (the file's name and purpose) goes, so the
    # header names its contributors but not the file: incomplete-header fires.
    repo.write("lab4/Final.glsl", long_clean.split("\n", 1)[1])
    repo.git("add", "lab4/Final.glsl")
    status = repo.git("diff", "--cached", "--name-status").stdout
    assert status.startswith("R"), status  # git sees R0xx: a rename with edits
    proc = repo.commit()
    assert proc.returncode != 0, proc.stdout + proc.stderr
    assert "lab4/Final.glsl:1:1: incomplete-header" in proc.stdout + proc.stderr


@pytest.mark.parametrize(
    "name", ['lab4/it\'s "Image".glsl', "lab4/tab\there.glsl", "lab4/ünïcode Image.glsl"]
)
def test_hook_lints_names_git_quotes(repo: Repo, name: str):
    repo.write(name, BAD)
    repo.git("add", "--", name)
    proc = repo.commit()
    assert proc.returncode != 0, proc.stdout + proc.stderr
    assert f"{name}:1:1: missing-header" in proc.stdout + proc.stderr
    repo.write(name, CLEAN)
    repo.git("add", "--", name)
    proc = repo.commit()
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert name in repo.committed()


def test_hook_uses_the_staged_configuration(repo: Repo):
    # The staged configuration turns missing-header off; the work tree's copy does not.
    repo.write("lab4/glslcheck.toml", 'ignore = ["missing-header"]\n')
    repo.write(
        "lab4/Image.glsl", BAD.replace("void mainImage", "// paint every pixel\nvoid mainImage")
    )
    repo.git("add", "lab4")
    (repo.root / "lab4/glslcheck.toml").write_text("", encoding="utf-8")
    proc = repo.commit()
    assert "missing-header" not in proc.stdout + proc.stderr
    assert "lab4/Image.glsl:" in proc.stdout + proc.stderr  # it was linted: its other findings show


def test_lint_staged_outside_a_repository(tmp_path: Path):
    proc = subprocess.run(
        [sys.executable, "-m", "glslcheck", "lint", "--staged"],
        cwd=tmp_path,
        env={**os.environ, "GIT_CEILING_DIRECTORIES": str(tmp_path.parent)},
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2 and "not inside a git work tree" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_hook_names_a_bad_staged_configuration_by_its_own_path(repo: Repo):
    repo.write("lab4/glslcheck.toml", "select = 3\n")
    repo.write("lab4/Image.glsl", CLEAN)
    repo.git("add", "lab4")
    proc = repo.commit()
    assert proc.returncode != 0
    assert "lab4/glslcheck.toml" in proc.stderr and "glslcheck-staged" not in proc.stderr, (
        proc.stderr
    )


def test_hook_leaves_large_non_shader_files_alone(repo: Repo, monkeypatch):
    repo.write("video.bin", "x" * 100_000)
    repo.write("lab4/Image.glsl", CLEAN)
    repo.git("add", "video.bin", "lab4/Image.glsl")
    monkeypatch.chdir(repo.root)
    for key, value in repo.env.items():
        monkeypatch.setenv(key, value)
    from glslcheck.lint.staged import staged_checkout

    with staged_checkout() as names:
        assert names == ["lab4/Image.glsl"]
        assert sorted(str(p) for p in Path(".").rglob("*") if p.is_file()) == ["lab4/Image.glsl"]


def test_hook_on_the_first_commit(tmp_path: Path):
    root = tmp_path / "fresh"
    root.mkdir()
    r = Repo(root)
    r.git("init", "-q", "-b", "main")
    assert (
        subprocess.run(
            [sys.executable, "-m", "glslcheck", "install-hook"],
            cwd=root,
            env=r.env,
            capture_output=True,
        ).returncode
        == 0
    )
    r.write("Image.glsl", BAD)
    r.git("add", "Image.glsl")
    proc = r.commit()
    assert proc.returncode != 0 and "Image.glsl:1:1: missing-header" in proc.stdout + proc.stderr


def test_hook_checks_out_the_index_common_tab_next_to_a_staged_image(repo: Repo, monkeypatch):
    repo.write("lab4/Common.glsl", "// committed helpers\nvec3 tint() { return vec3(0.5); }\n")
    repo.git("add", "lab4/Common.glsl")
    repo.git("commit", "-q", "--no-verify", "-m", "helpers")
    repo.write("lab4/Image.glsl", CLEAN)
    repo.git("add", "lab4/Image.glsl")
    (repo.root / "lab4/Common.glsl").write_text("// the work tree's unstaged copy\n")
    monkeypatch.chdir(repo.root)
    for key, value in repo.env.items():
        monkeypatch.setenv(key, value)
    from glslcheck.lint.staged import staged_checkout

    with staged_checkout() as names:
        assert names == ["lab4/Image.glsl"]  # Common is context, not a target
        assert (
            Path("lab4/Common.glsl").read_text()
            == "// committed helpers\nvec3 tint() { return vec3(0.5); }\n"
        )
