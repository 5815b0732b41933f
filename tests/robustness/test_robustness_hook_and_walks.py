"""The pre-commit hook and the folder walk under unlucky repositories and trees.

What the hook runs (`glslcheck lint --staged`, from this checkout: the installed hook runs the
installed glslcheck, which may be another checkout) in a temporary git repository
(test_security_hook's Repo): a submodule or a symbolic link named like a shader tab is no shader
text and must neither block the commit nor be linted through its target; a commit of more folders
than a command line holds must go through; a second `install-hook --force` must keep the first
backup. The walk of check, lint, parse and report must enter each real folder once, whatever
symbolic links point back up the tree.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from test_security_hook import BAD, CLEAN, Repo, new_repo

HOOK_MARKER = "glslcheck-managed-hook"
CHECKOUT = str(Path(__file__).resolve().parents[2])  # the glslcheck these tests run


@pytest.fixture
def repo(tmp_path: Path) -> Repo:
    return new_repo(tmp_path)


def _hook(repo: Repo) -> subprocess.CompletedProcess:
    """What the pre-commit hook runs, on the repository's index: exit 0 lets the commit through."""
    return _glslcheck("lint", "--staged", cwd=repo.root, env=repo.env)


def _glslcheck(*args: str, cwd: Path, env: dict | None = None) -> subprocess.CompletedProcess:
    env = {**(os.environ if env is None else env), "PYTHONPATH": CHECKOUT}
    return subprocess.run(
        [sys.executable, "-m", "glslcheck", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )


def _head(repo: Repo) -> str:
    return repo.git("rev-parse", "HEAD").stdout.strip()


def _stage(repo: Repo, mode: str, name: str, object_id: str) -> None:
    repo.git("update-index", "--add", "--cacheinfo", f"{mode},{object_id},{name}")


# A submodule (an index entry of mode 160000) ----------------------------------------------------


@pytest.mark.parametrize("name", ["Image", "lab4/Image", "lab4/Common.glsl"])
def test_hook_skips_a_submodule_named_as_a_tab(repo: Repo, name: str):
    _stage(repo, "160000", name, _head(repo))  # any commit id: the hook must not look inside
    proc = _hook(repo)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert f"{name}: note: a submodule, not a shader file; not linted" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_hook_lints_a_shader_beside_a_submodule_named_common(repo: Repo):
    _stage(repo, "160000", "lab4/Common", _head(repo))
    repo.write("lab4/Image.glsl", BAD)
    repo.git("add", "lab4/Image.glsl")
    proc = _hook(repo)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    assert "lab4/Image.glsl:1:1: missing-header" in proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr


# A symbolic link (mode 120000) ------------------------------------------------------------------


def test_hook_does_not_lint_a_staged_symlink_through_its_target(repo: Repo, tmp_path: Path):
    target = tmp_path / "elsewhere.glsl"
    target.write_text(BAD, encoding="utf-8")  # findings, were it linted
    os.symlink(target, repo.root / "Image.glsl")
    repo.git("add", "Image.glsl")
    assert repo.git("ls-files", "-s", "Image.glsl").stdout.startswith("120000 ")
    proc = _hook(repo)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "missing-header" not in proc.stdout + proc.stderr
    assert "Image.glsl: note: a symbolic link, not a shader file; not linted" in proc.stderr


def test_hook_lints_a_symlink_replaced_by_a_shader_file(repo: Repo, tmp_path: Path):
    target = tmp_path / "elsewhere.glsl"
    target.write_text(CLEAN, encoding="utf-8")
    os.symlink(target, repo.root / "Image.glsl")
    repo.git("add", "Image.glsl")
    repo.git("commit", "-q", "--no-verify", "-m", "a link")
    (repo.root / "Image.glsl").unlink()
    repo.write("Image.glsl", BAD)  # now a regular file: git sees a type change (T)
    repo.git("add", "Image.glsl")
    assert repo.git("diff", "--cached", "--name-status").stdout.startswith("T")
    proc = _hook(repo)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    assert "Image.glsl:1:1: missing-header" in proc.stdout + proc.stderr


def test_hook_context_tabs_are_regular_files_only(repo: Repo, tmp_path: Path, monkeypatch):
    target = tmp_path / "common.glsl"
    target.write_text("// helpers\nvec3 tint() { return vec3(0.5); }\n", encoding="utf-8")
    (repo.root / "lab4").mkdir()
    os.symlink(target, repo.root / "lab4/Common.glsl")
    repo.write("lab4/Image.glsl", CLEAN)
    repo.git("add", "lab4")
    monkeypatch.chdir(repo.root)
    for key, value in repo.env.items():
        monkeypatch.setenv(key, value)
    from glslcheck.lint.staged import staged_checkout

    skipped: list[tuple[str, str]] = []
    with staged_checkout(skipped) as names:
        assert names == ["lab4/Image.glsl"]
        assert sorted(str(p) for p in Path(".").rglob("*") if not p.is_dir()) == ["lab4/Image.glsl"]
    assert skipped == [("lab4/Common.glsl", "a symbolic link")]


# A commit of more folders than a command line holds -------------------------------------------


def test_hook_commits_more_folders_than_a_command_line_holds(repo: Repo):
    repo.write("lab4/Common.glsl", "// shared helpers\nvec3 tint() { return vec3(0.5); }\n")
    repo.git("add", "lab4/Common.glsl")
    repo.git("commit", "-q", "--no-verify", "-m", "helpers")  # context for the Image tab below
    arg_max = os.sysconf("SC_ARG_MAX")
    if arg_max <= 0 or arg_max > 64_000_000:
        pytest.skip(f"command-line limit {arg_max}: too large to reach in a test")
    blob = repo.git("hash-object", "-w", "--stdin", check=False).stdout.strip()  # the empty file
    folder = "f" * 200
    # Each staged file's folder adds its two configuration names (over 200 bytes each) to the
    # pathspecs of one git command before the fix: enough folders to pass the limit twice.
    count = 2 * arg_max // (2 * (len(folder) + len("/glslcheck.toml"))) + 1
    listing = "".join(f"100644 {blob}\t{folder}{i:07d}/notes.md\n" for i in range(count))
    subprocess.run(
        ["git", "update-index", "--add", "--index-info"],
        cwd=repo.root,
        env=repo.env,
        input=listing,
        text=True,
        check=True,
    )
    repo.write("lab4/Image.glsl", BAD)
    repo.git("add", "lab4")
    proc = _hook(repo)
    assert "Traceback" not in proc.stderr, proc.stderr[-2000:]
    assert proc.returncode == 1, proc.stderr[-2000:]
    assert "lab4/Image.glsl:1:1: missing-header" in proc.stdout + proc.stderr
    repo.write("lab4/Image.glsl", CLEAN)
    repo.git("add", "lab4/Image.glsl")
    proc = _hook(repo)
    assert proc.returncode == 0, proc.stdout + proc.stderr[-2000:]


def test_index_lookups_in_small_runs_find_what_one_run_finds(repo: Repo, monkeypatch):
    for lab in ("lab1", "lab2", "lab3 with spaces", "lab4/deeper"):
        repo.write(f"{lab}/Image.glsl", CLEAN)
        repo.write(f"{lab}/Common.glsl", "// helpers\n")
        repo.write(f"{lab}/glslcheck.toml", "")
    repo.write("glslcheck.toml", "")
    repo.git("add", ".")
    monkeypatch.chdir(repo.root)
    for key, value in repo.env.items():
        monkeypatch.setenv(key, value)
    from glslcheck.lint import staged

    def written() -> tuple[list[str], list[str]]:
        with staged.staged_checkout() as names:
            return names, sorted(str(p) for p in Path(".").rglob("*") if p.is_file())

    whole = written()
    monkeypatch.setattr(staged, "ARGS_BUDGET", 1)  # one pathspec per git command
    assert written() == whole
    assert len(whole[1]) == 4 * 3 + 1


# install-hook --force, twice -------------------------------------------------------------------


def test_install_hook_force_twice_keeps_every_hook_it_replaced(repo: Repo):
    hooks = repo.root / ".git" / "hooks"
    assert _glslcheck("install-hook", cwd=repo.root, env=repo.env).returncode == 0
    theirs = [
        "#!/bin/sh\necho 'the first hook of my own'\n",
        "#!/bin/sh\necho 'a tool wrote this one later'\n",
    ]
    for text in theirs:
        (hooks / "pre-commit").write_text(text, encoding="utf-8")
        proc = _glslcheck("install-hook", "--force", cwd=repo.root, env=repo.env)
        assert proc.returncode == 0 and "replaced" in proc.stdout, proc.stderr
        assert HOOK_MARKER in (hooks / "pre-commit").read_text(encoding="utf-8")
    proc = _glslcheck(
        "install-hook", "--force", cwd=repo.root, env=repo.env
    )  # its own hook: updated, no backup
    assert proc.returncode == 0 and "updated" in proc.stdout, proc.stderr
    kept = sorted(hooks.glob("pre-commit.glslcheck-backup*"))
    assert [p.read_text(encoding="utf-8") for p in kept] == theirs
    assert [p.name for p in kept] == [
        "pre-commit.glslcheck-backup",
        "pre-commit.glslcheck-backup.1",
    ]


# Folders holding symbolic links to themselves or above ------------------------------------------


def _looping_tree(root: Path, outside: Path) -> None:
    (root / "lab1").mkdir(parents=True)
    (root / "lab1" / "Image.glsl").write_text(CLEAN, encoding="utf-8")
    (root / "notes" / "deeper").mkdir(parents=True)
    (root / "notes" / "loose.glsl").write_text(CLEAN, encoding="utf-8")
    for link, target in (
        ("again", "."),
        ("self", "."),
        ("notes/up", ".."),
        ("notes/deeper/top", "../.."),
        ("notes/deeper/here", "."),
        ("notes/absolute", str(root)),
        ("shared", str(outside)),
    ):
        os.symlink(target, root / link)
    (outside / "lab9").mkdir(parents=True)
    (outside / "lab9" / "Image.glsl").write_text(CLEAN, encoding="utf-8")
    os.symlink("..", outside / "lab9" / "back")


# Every shader of the looping tree once, under its own name; a link out of the tree (shared) is
# still followed. lint lints only files inside the folder it is given, so not shared/lab9.
SHADERS = ["course/lab1", "course/notes/loose.glsl", "course/shared/lab9"]


def test_walk_enters_each_real_folder_once(tmp_path: Path):
    _looping_tree(tmp_path / "course", tmp_path / "outside")
    code = (
        "from glslcheck.shadertoy.sources import find_shaders\nfor s in "
        "find_shaders(['course']): print(s.root)\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", code],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "PYTHONPATH": CHECKOUT},
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines() == SHADERS


@pytest.mark.parametrize(
    "command, summary",
    [
        (["lint"], f"no findings in {len(SHADERS) - 1} files"),
        (["check"], f"checked {len(SHADERS)} programs: {len(SHADERS)} clean"),
        (["parse"], f"parsed {len(SHADERS)} of {len(SHADERS)} programs"),
        (
            ["report", "--no-webgl", "--no-bench", "--size", "8x8", "-o", "report.html"],
            f"{len(SHADERS)} shaders, all clean",
        ),
    ],
)
def test_commands_walk_a_folder_that_links_to_itself(
    tmp_path: Path, command: list[str], summary: str
):
    _looping_tree(tmp_path / "course", tmp_path / "outside")
    proc = _glslcheck(command[0], "course", *command[1:], cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert summary in proc.stdout + proc.stderr
