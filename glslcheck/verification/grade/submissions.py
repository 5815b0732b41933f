"""What a class hands in, and how each hand-in becomes a shader on disk.

A submission is one team's work, given as

- a folder of Shadertoy tab files (or a folder holding one such folder), or a single tab file;
- a git repository (a local path or any URL `git clone` takes) and the branch that holds the
  finished lab (`--branch`, or the roster's `branch` column).

A roster is a CSV file with a header naming at least `team`, `repo` and `branch` (the hand-in
of the assignment: the contributors' names, a public repository, the branch), in any order and
any letter case, and optionally `contributors` (names separated by `;` or `,` inside the
quoted cell) and `path` (the folder inside the repository that holds the tabs, when the branch
holds several shaders). A relative `repo` path is read from the roster's folder.

A repository is cloned (one branch, no tags, symbolic links checked out as plain files so that
no file outside the clone is read, no prompt for credentials) into a temporary folder that is
removed when the submission is graded. Every failure (no such repository or branch, nothing that
looks like a shader, two candidate shaders) is a `SubmissionError` whose message says what a TA
should tell the team.
"""

from __future__ import annotations

import csv
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from ...base.diagnostics import InputError
from ...shadertoy.sources import Shader, find_shaders, posix_path

GIT_SECONDS = 300  # a clone of a coursework repository over the network: generous, never endless
ROSTER_COLUMNS = ("team", "repo", "branch")
OPTIONAL_COLUMNS = ("contributors", "path")


class SubmissionError(Exception):
    """A submission that cannot be graded; the message is the reason shown in its row."""


@dataclass
class Submission:
    """One team's hand-in: `source` is a folder, a file, a repository path or a URL, as the
    TA wrote it (every message shows it so); a relative path is read from `base`."""

    team: str
    source: str
    branch: str | None = None
    contributors: list[str] = field(default_factory=list)
    path: str | None = None  # the folder inside the checkout that holds the tabs
    base: str = ""  # the roster's folder; "" for the current one

    @property
    def location(self) -> str:
        """`source` as a path or URL to open or clone."""
        if not self.base or _is_url(self.source) or os.path.isabs(self.source):
            return self.source
        return os.path.join(self.base, self.source)


def from_paths(paths: list[str], branch: str | None = None) -> list[Submission]:
    """A submission per command-line path, named after the path's last part."""
    out = []
    for p in paths:
        name = Path(posix_path(p)).name or str(p)
        if name.endswith(".git"):
            name = name[:-4]
        out.append(Submission(team=name, source=str(p), branch=branch))
    return out


def read_roster(path: str | os.PathLike) -> list[Submission]:
    """The submissions of a roster CSV (see the module docstring); InputError naming the file
    and line for a missing column, an empty required cell or two rows of one team."""
    try:
        with open(path, encoding="utf-8-sig", newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise InputError(f"{path}: error: cannot read the roster ({e.strerror or e})") from None
    except (UnicodeDecodeError, csv.Error) as e:
        raise InputError(f"{path}: error: the roster is not a UTF-8 CSV file ({e})") from None
    if not rows:
        raise InputError(
            f"{path}:1:1: error: the roster is empty; its first line names the columns"
        )
    header = [h.strip().lower() for h in rows[0]]
    missing = [c for c in ROSTER_COLUMNS if c not in header]
    if missing:
        raise InputError(
            f"{path}:1:1: error: the roster's header has no {', '.join(missing)} column "
            f"(it needs {', '.join(ROSTER_COLUMNS)}; optional: {', '.join(OPTIONAL_COLUMNS)})"
        )
    col = {
        name: header.index(name) for name in (*ROSTER_COLUMNS, *OPTIONAL_COLUMNS) if name in header
    }
    base = Path(path).parent
    out: list[Submission] = []
    seen: dict[str, int] = {}
    for number, row in enumerate(rows[1:], 2):
        if not any(cell.strip() for cell in row):
            continue

        def cell(name: str) -> str:
            i = col.get(name)
            return row[i].strip() if i is not None and i < len(row) else ""

        for name in ROSTER_COLUMNS:
            if not cell(name):
                raise InputError(
                    f"{path}:{number}:{col[name] + 1}: error: the {name} cell is empty"
                )
        team = cell("team")
        if team in seen:
            raise InputError(
                f"{path}:{number}:{col['team'] + 1}: error: "
                f"team {team!r} is on line {seen[team]} too"
            )
        seen[team] = number
        names = cell("contributors").replace(";", ",").split(",")
        out.append(
            Submission(
                team=team,
                source=cell("repo"),
                base=str(base),
                branch=cell("branch"),
                contributors=[n.strip() for n in names if n.strip()],
                path=cell("path") or None,
            )
        )
    return out


def _is_url(text: str) -> bool:
    """Whether git reads `text` as a remote address (scheme://... or scp-like user@host:path)."""
    if "://" in text:
        return True
    head = text.split("/", 1)[0]
    return ":" in head and not os.path.exists(text)


class Checkout:
    """The files of a submission on disk for the time of the `with` block: the folder or file
    itself, or a clone of the repository's branch in a temporary folder (removed after)."""

    def __init__(self, submission: Submission):
        self.submission = submission
        self.root = ""
        self._tmp: str | None = None

    def __enter__(self) -> Checkout:
        s = self.submission
        if s.branch is None:
            if not os.path.exists(s.location):
                raise SubmissionError(f"{s.source}: no such file or folder")
            self.root = s.location
            return self
        self._tmp = tempfile.mkdtemp(prefix="glslcheck-grade-")
        try:
            self.root = clone_branch(
                s.location, s.branch, os.path.join(self._tmp, "checkout"), s.source
            )
        except BaseException:
            self.__exit__(None, None, None)
            raise
        return self

    def __exit__(self, *exc) -> None:
        if self._tmp is not None:
            shutil.rmtree(self._tmp, ignore_errors=True)
            self._tmp = None

    def relative(self, path: str) -> str:
        """`path` as the team sees it: relative to the top of their repository or folder."""
        if self._tmp is None:
            return path
        try:
            return os.path.relpath(path, self.root)
        except ValueError:
            return path


def _git(args: list[str], what: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, GIT_TERMINAL_PROMPT="0", GIT_SSH_COMMAND="ssh -o BatchMode=yes")
    try:
        return subprocess.run(
            ["git", *args],
            capture_output=True,
            text=True,
            errors="replace",
            env=env,
            timeout=GIT_SECONDS,
            stdin=subprocess.DEVNULL,
        )
    except FileNotFoundError:
        raise SubmissionError("git is not installed; it is needed to read repositories") from None
    except subprocess.TimeoutExpired:
        raise SubmissionError(f"{what}: git took over {GIT_SECONDS} s; gave up") from None


def _git_message(result: subprocess.CompletedProcess) -> str:
    """git's own reason: its first fatal or error line (the advice after it is git's)."""
    lines = [ln.strip() for ln in result.stderr.splitlines() if ln.strip()]
    for ln in lines:
        if ln.startswith(("fatal: ", "error: ")):
            return ln.split(": ", 1)[1]
    return lines[-1] if lines else f"git exited with status {result.returncode}"


def branches(repo: str, name: str | None = None) -> list[str]:
    """The branch names of a repository (SubmissionError, naming it `name`, when it cannot be
    read)."""
    name = name or repo
    if not _is_url(repo) and not os.path.exists(repo):
        raise SubmissionError(f"{name}: no such repository (no such folder)")
    result = _git(["-c", "protocol.file.allow=always", "ls-remote", "--heads", "--", repo], name)
    if result.returncode != 0:
        raise SubmissionError(f"{name}: not a repository git can read ({_git_message(result)})")
    return sorted(
        line.split("refs/heads/", 1)[1]
        for line in result.stdout.splitlines()
        if "refs/heads/" in line
    )


def clone_branch(repo: str, branch: str, dest: str, name: str | None = None) -> str:
    """Clone the one branch of `repo` into `dest` (see the module docstring); the folder.
    Messages name the repository `name` (default `repo`)."""
    name = name or repo
    names = branches(repo, name)
    if branch not in names:
        there = ", ".join(names[:12]) + (", ..." if len(names) > 12 else "") if names else "none"
        raise SubmissionError(f"{name}: no branch {branch!r} (branches: {there})")
    result = _git(
        [
            "-c",
            "protocol.file.allow=always",
            "-c",
            "core.symlinks=false",
            "clone",
            "--quiet",
            "--single-branch",
            "--no-tags",
            "--branch",
            branch,
            "--",
            repo,
            dest,
        ],
        name,
    )
    if result.returncode != 0:
        raise SubmissionError(f"{name}: cannot clone branch {branch!r} ({_git_message(result)})")
    return dest


def find_tab_files(root: str) -> list[Shader]:
    """Every shader under `root` found as `glslcheck lint` finds them (a folder of tab files is a
    shader, a loose shader file is one of its own): the one place grade looks for tab files."""
    return find_shaders([root])


def submission_shader(root: str, path: str | None = None) -> Shader:
    """The one shader a submission hands in: under `path` (inside `root`) when given; else the
    only shader with an Image tab, or of several the only one whose Image tab defines
    `mainImage` (Shadertoy's entry point: a README.txt has none). SubmissionError otherwise."""
    where = root
    if path is not None:
        where = os.path.join(root, path)
        if not os.path.exists(where):
            raise SubmissionError(f"{path}: no such file or folder in the submission")
    if os.path.isdir(where) and not any(True for _ in os.scandir(where)):
        raise SubmissionError("the submission is empty: no tab files")
    try:
        shaders = find_tab_files(where)
    except InputError as e:  # a binary file, an unreadable one, a folder of no tab files
        raise SubmissionError(str(e).removeprefix("error: ")) from None
    with_image = [s for s in shaders if s.image is not None]
    if not with_image:
        found = ", ".join(src.path for s in shaders for src in s.sources())
        raise SubmissionError(
            "no Image tab (the tab Shadertoy renders; a file named Image.txt or Image.glsl)"
            + (f"; found only {found}" if found else "")
        )
    if len(with_image) > 1:
        entry = [s for s in with_image if s.image is not None and "mainImage" in s.image.text]
        if len(entry) == 1:
            return entry[0]
        names = ", ".join(s.root for s in (entry or with_image))
        raise SubmissionError(
            f"{len(entry or with_image)} shaders in the submission ({names}); name the folder "
            "to grade (the roster's path column)"
        )
    return with_image[0]
