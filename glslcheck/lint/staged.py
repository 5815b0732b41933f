"""What a pre-commit hook lints: the staged index, not the work tree.

`glslcheck lint --staged` (the command the hook `glslcheck install-hook` writes runs) lints the
version of each staged shader file that the commit will hold. A clean working copy over a bad
staged version must not let the bad version through, and a bad working copy over a clean staged
one must not stop the commit.

How: the staged files that were added, copied, modified or renamed (`--diff-filter=ACMR`, so a
renamed-and-edited file, `R088`, is linted under its new name) are listed NUL-separated (`-z`,
so names with quotes, tabs or newlines arrive as they are), and their index versions are written
with `git checkout-index` into a private temporary folder, with what linting them needs from the
index: the configuration files (glslcheck.toml, pyproject.toml) of their folders and the folders
above (written first: their tab-patterns say which names are shaders, and only shader files are
written), and the Shadertoy tab files next to them (an Image tab is compiled after its sibling
Common tab). The linter then runs in that folder on the repository-relative names, so every
message names the user's own path (relative to the top of the work tree) and line.

Git's environment is kept: during `git commit -a` or `git commit PATH` git points
GIT_INDEX_FILE at a temporary index, and that is the one to lint.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
import tempfile
from pathlib import PurePosixPath

from ..base.diagnostics import InputError

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up (issue 18)
if TYPE_CHECKING:
    from typing import Iterator

CONFIG_FILES = ("glslcheck.toml", "pyproject.toml")


def _git(*args: str, cwd: str | None = None, stdin: bytes | None = None) -> bytes:
    try:
        proc = subprocess.run(["git", *args], cwd=cwd, input=stdin, capture_output=True)
    except FileNotFoundError:
        raise InputError("glslcheck lint --staged: error: git is not installed") from None
    if proc.returncode != 0:
        message = proc.stderr.decode("utf-8", "replace").strip().splitlines()
        raise InputError(f"glslcheck lint --staged: error: git {args[0]} failed"
                         + (f" ({message[-1]})" if message else ""))
    return proc.stdout


def _names(out: bytes) -> list[str]:
    """NUL-separated git paths as str (undecodable bytes kept via surrogateescape, as os does)."""
    return [os.fsdecode(n) for n in out.split(b"\0") if n]


def staged_names(top: str) -> list[str]:
    """The repository-relative names of the staged files that were added, copied, modified or
    renamed (the new name), in git's order."""
    return _names(_git("diff", "--cached", "--name-only", "-z", "--diff-filter=ACMR", cwd=top))


def _index_names(top: str, pathspecs: list[str]) -> list[str]:
    """The index entries matching literal pathspecs."""
    if not pathspecs:
        return []
    return _names(_git("--literal-pathspecs", "ls-files", "-z", "--cached", "--", *pathspecs, cwd=top))


def _config_names(top: str, staged: list[str]) -> list[str]:
    """The configuration files in the index in the staged files' folders and above them."""
    above = {d for n in staged for d in PurePosixPath(n).parents}
    return _index_names(top, [str(d / c) if str(d) != "." else c for d in sorted(above) for c in CONFIG_FILES])


def _sibling_tabs(top: str, names: list[str]) -> list[str]:
    """The Shadertoy tab files in the index next to `names` (an Image tab needs its Common)."""
    from ..shadertoy.sources import tab_name

    folders = {PurePosixPath(n).parent for n in names}
    siblings = _index_names(top, [f"{d}/" if str(d) != "." else "." for d in sorted(folders)])
    return [n for n in siblings if PurePosixPath(n).parent in folders and tab_name(n) is not None]


def _shader_names(names: list[str]) -> list[str]:
    """The names that are shader files by the (checked out) configuration of their folder."""
    from .config import ConfigFinder
    from .engine import is_shader_name
    from .rules import rule_names

    finder = ConfigFinder({}, rule_names())
    return [n for n in names if is_shader_name(n, finder.for_file(n))]


def _checkout(top: str, folder: str, names: list[str]) -> None:
    if names:
        listing = b"".join(os.fsencode(n) + b"\0" for n in names)
        _git("checkout-index", "-z", "--stdin", f"--prefix={folder}/", cwd=top, stdin=listing)


@contextlib.contextmanager
def staged_checkout() -> Iterator[list[str]]:
    """Write the staged shader files (and their context) into a temporary folder, enter it, and
    yield their names (relative to it and to the top of the work tree); cwd and the folder are
    restored and removed afterwards. InputError outside a git work tree."""
    try:
        top = os.fsdecode(_git("rev-parse", "--show-toplevel").rstrip(b"\n"))
    except InputError:
        raise InputError("glslcheck lint --staged: error: not inside a git work tree") from None
    staged = staged_names(top)
    # Mode 0700, so no other user writes in it; inside the git folder, so the configuration
    # search above it meets the repository's folders (as it would for the work tree's files),
    # not the shared temporary folder.
    git_dir = os.fsdecode(_git("rev-parse", "--absolute-git-dir", cwd=top).rstrip(b"\n"))
    try:
        folder = tempfile.mkdtemp(prefix="glslcheck-staged-", dir=git_dir)
    except OSError:
        folder = tempfile.mkdtemp(prefix="glslcheck-staged-")
    cwd = os.getcwd()
    try:
        # The configuration first: it says which names are shaders (tab-patterns); then only
        # those are written, so a large staged binary is never copied.
        _checkout(top, folder, _config_names(top, staged))
        os.chdir(folder)
        shaders = _shader_names(staged)
        _checkout(top, folder, list(dict.fromkeys(shaders + _sibling_tabs(top, shaders))))
        yield shaders
    except InputError as e:  # e.g. a bad staged configuration file: name it as the user does
        message = str(e)
        for prefix in {folder, os.path.realpath(folder)}:
            message = message.replace(prefix + os.sep, "")
        raise InputError(message) from None
    finally:
        os.chdir(cwd)
        shutil.rmtree(folder, ignore_errors=True)
