"""Install a git pre-commit hook that runs `glslcheck lint` on the staged shader files.

The hook is a plain POSIX sh script in the repository's hooks folder (`core.hooksPath` is
honoured). It runs `glslcheck lint --staged` (see glslcheck/lint/staged.py): the staged version of
the files that were added, copied, modified, renamed or changed type and are shader files (.glsl,
.frag, a Shadertoy tab name, or a `tab-patterns` glob of the configuration), and stops the commit
when there is a finding; `git commit --no-verify` skips it once. It runs the Python that installed
it in isolated mode, so a `glslcheck/` folder in the repository is never imported. A hook that
glslcheck did not write is left alone unless --force is given (it is then kept as
pre-commit.glslcheck-backup, or the first free pre-commit.glslcheck-backup.N: an earlier backup is
never overwritten). Exit 2 outside a git repository.
"""

from __future__ import annotations

import argparse
import os
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

from ...base.diagnostics import InputError

MARKER = "# glslcheck-managed-hook: written by `glslcheck install-hook`"

HOOK_TEMPLATE = """#!/bin/sh
{marker}
# Lints the staged version of the staged shader files with glslcheck; a finding stops the commit.
# Skip it once with `git commit --no-verify`; reinstall with `glslcheck install-hook`.

# The installed glslcheck, run isolated ({flags}): a `glslcheck/` folder in the repository is
# never imported in its place.
PYTHON={python}
if [ -x "$PYTHON" ]; then
    exec "$PYTHON" {flags} -m glslcheck lint --staged
elif command -v glslcheck >/dev/null 2>&1; then
    exec glslcheck lint --staged
else
    echo "glslcheck pre-commit hook: glslcheck is not installed ($PYTHON is gone)" >&2
    exit 1
fi
"""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--force", action="store_true", help="replace a pre-commit hook glslcheck did not write"
    )


def hook_text(python: str | None = None) -> str:
    python = python or sys.executable
    return HOOK_TEMPLATE.format(
        marker=MARKER, python=shlex.quote(python), flags=isolation_flags(python)
    )


def isolation_flags(python: str) -> str:
    """`-I` (isolated: no current folder or script folder on sys.path, no PYTHON* variables, no
    user site-packages) when `python -I` imports this very glslcheck; `-E -P` (the first two
    only) when glslcheck is installed in the user's site-packages, which -I leaves out."""
    package_init = sys.modules[
        "glslcheck"
    ].__file__  # this glslcheck (loaded: it runs this command)
    with tempfile.TemporaryDirectory() as neutral:
        try:
            proc = subprocess.run(
                [python, "-I", "-c", "import glslcheck; print(glslcheck.__file__)"],
                cwd=neutral,
                capture_output=True,
                text=True,
                timeout=60,
            )
        except (OSError, subprocess.TimeoutExpired):
            return "-I"
    return "-I" if proc.stdout.strip() == package_init else "-E -P"


def hook_path(cwd: str | os.PathLike | None = None) -> Path:
    """The pre-commit hook file of the repository at `cwd`; InputError outside a repository."""
    try:
        proc = subprocess.run(
            ["git", "rev-parse", "--path-format=absolute", "--git-path", "hooks/pre-commit"],
            cwd=cwd,
            capture_output=True,
            text=True,
        )
    except FileNotFoundError:
        raise InputError("glslcheck install-hook: error: git is not installed") from None
    if proc.returncode != 0:
        raise InputError("glslcheck install-hook: error: not inside a git repository")
    return Path(proc.stdout.strip())


def backup_path(path: Path) -> Path:
    """Where a foreign hook at `path` is kept: the first name of pre-commit.glslcheck-backup,
    pre-commit.glslcheck-backup.1, ... that names nothing yet (not even a dangling link)."""
    backup = path.with_name("pre-commit.glslcheck-backup")
    n = 0
    while os.path.lexists(backup):
        n += 1
        backup = path.with_name(f"pre-commit.glslcheck-backup.{n}")
    return backup


def install(
    cwd: str | os.PathLike | None = None, force: bool = False
) -> tuple[Path, str, Path | None]:
    """Write the hook; returns its path, what happened ("installed", "updated", "replaced") and
    where a replaced hook was kept."""
    path = hook_path(cwd)
    status = "installed"
    backup = None
    if path.exists():
        old = path.read_text(encoding="utf-8", errors="replace")
        if MARKER in old:
            status = "updated"
        elif not force:
            raise InputError(
                f"{path}: error: a pre-commit hook that glslcheck did not write is already there; "
                "run `glslcheck install-hook --force` to replace it (it is kept as "
                f"{backup_path(path).name})"
            )
        else:
            backup = backup_path(path)
            path.replace(backup)
            status = "replaced"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(hook_text(), encoding="utf-8")
    path.chmod(0o755)
    return path, status, backup


def run(args: argparse.Namespace) -> int:
    path, status, backup = install(force=args.force)
    kept = f" (the one it replaced is kept as {backup})" if backup else ""
    print(f"glslcheck: {status} the pre-commit hook {path}{kept}")
    return 0
