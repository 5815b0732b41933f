"""What a pre-commit hook lints: the staged index, not the work tree.

`glslcheck lint --staged` (the command the hook `glslcheck install-hook` writes runs) lints the
version of each staged shader file that the commit will hold. A clean working copy over a bad
staged version must not let the bad version through, and a bad working copy over a clean staged
one must not stop the commit.

How: the staged files that were added, copied, modified, renamed or changed type
(`--diff-filter=ACMRT`, so a renamed-and-edited file, `R088`, is linted under its new name) are
listed NUL-separated (`-z`, so names with quotes, tabs or newlines arrive as they are) with their
index modes: only regular files are shader files. A symbolic link (mode 120000) holds a path, not
a shader's text, and a submodule (160000) is another repository's commit, whatever their names
say; both are left out (and named in `skipped`). Their index versions are written
with `git checkout-index` into a private temporary folder, with what linting them needs from the
index: the configuration files (glslcheck.toml, pyproject.toml) of their folders and the folders
above (written first: their tab-patterns say which names are shaders, and only shader files are
written), and the Shadertoy tab files next to them (an Image tab is compiled after its sibling
Common tab). The linter then runs in that folder on the repository-relative names, so every
message names the user's own path (relative to the top of the work tree) and line.

Paths go to git on stdin (checkout-index) or in runs of bounded size (ls-files reads no pathspecs
from stdin), so a commit of any number of folders stays under the system's command-line limit.

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

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

CONFIG_FILES = ("glslcheck.toml", "pyproject.toml")
# Bytes of pathspecs per git command: far under the command-line limit (Linux: at least 128 kB).
ARGS_BUDGET = 64_000


def _git(*args: str, cwd: str | None = None, stdin: bytes | None = None) -> bytes:
    try:
        proc = subprocess.run(["git", *args], cwd=cwd, input=stdin, capture_output=True)
    except FileNotFoundError:
        raise InputError("glslcheck lint --staged: error: git is not installed") from None
    if proc.returncode != 0:
        message = proc.stderr.decode("utf-8", "replace").strip().splitlines()
        command = next(a for a in args if not a.startswith("-"))
        raise InputError(
            f"glslcheck lint --staged: error: git {command} failed"
            + (f" ({message[-1]})" if message else "")
        )
    return proc.stdout


def _names(out: bytes) -> list[str]:
    """NUL-separated git paths as str (undecodable bytes kept via surrogateescape, as os does)."""
    return [os.fsdecode(n) for n in out.split(b"\0") if n]


# Index modes that are not a file's text: what a staged entry of that mode is.
NOT_FILES = {"120000": "a symbolic link", "160000": "a submodule"}


def _is_regular(mode: str) -> bool:
    return mode.startswith("100")  # 100644 or 100755 (git writes no other file mode)


def staged_entries(top: str) -> list[tuple[str, str, str]]:
    """(index mode, object id, repository-relative name) of each staged entry that was added,
    copied, modified, renamed (the new name) or changed type, in git's order."""
    fields = _names(_git("diff", "--cached", "--raw", "-z", "--diff-filter=ACMRT", cwd=top))
    # `-z --raw`: ":old-mode new-mode old-id new-id status" then the path (two paths for R and C).
    entries = []
    i = 0
    while i < len(fields):
        meta = fields[i].split()
        paths = 2 if meta[-1][:1] in ("R", "C") else 1
        entries.append((meta[1], meta[3], fields[i + paths]))
        i += 1 + paths
    return entries


def _index_names(top: str, pathspecs: list[str]) -> list[str]:
    """The regular files in the index matching literal pathspecs."""
    names: list[str] = []
    for chunk in _chunks(pathspecs):
        out = _git("--literal-pathspecs", "ls-files", "-z", "--stage", "--", *chunk, cwd=top)
        # `--stage -z`: "mode object stage\tpath" per entry.
        entries = [line.split("\t", 1) for line in _names(out)]
        names.extend(name for meta, name in entries if _is_regular(meta.split(" ", 1)[0]))
    return list(dict.fromkeys(names))


def _chunks(args: list[str], budget: int = ARGS_BUDGET) -> Iterator[list[str]]:
    """`args` in runs of at most `budget` bytes (each at least one argument): `git ls-files` takes
    its pathspecs only as arguments, and a command line over the system's limit fails."""
    chunk: list[str] = []
    size = 0
    for arg in args:
        cost = len(os.fsencode(arg)) + 1 + 8  # the string, its NUL and its pointer
        if chunk and size + cost > budget:
            yield chunk
            chunk, size = [], 0
        chunk.append(arg)
        size += cost
    if chunk:
        yield chunk


def _config_names(top: str, staged: list[str]) -> list[str]:
    """The configuration files in the index in the staged files' folders and above them."""
    above = {d for n in staged for d in PurePosixPath(n).parents}
    return _index_names(
        top, [str(d / c) if str(d) != "." else c for d in sorted(above) for c in CONFIG_FILES]
    )


def _sibling_tabs(top: str, names: list[str]) -> list[str]:
    """The Shadertoy tab files in the index next to `names` (an Image tab needs its Common)."""
    from ..shadertoy.sources import tab_name

    folders = {PurePosixPath(n).parent for n in names}
    siblings = _index_names(top, [f"{d}/" if str(d) != "." else "." for d in sorted(folders)])
    return [n for n in siblings if PurePosixPath(n).parent in folders and tab_name(n) is not None]


def _shader_names(names: list[str], texts: dict[str, str] | None = None) -> list[str]:
    """The names that are shader files by the (checked out) configuration of their folder and,
    for a name that leaves it open (a `.txt` or extension-less file), by their staged text."""
    from .config import ConfigFinder
    from .engine import is_shader_file
    from .rules import rule_names

    finder = ConfigFinder({}, rule_names())
    texts = texts or {}
    return [n for n in names if is_shader_file(n, finder.for_file(n), texts.get(n, ""))]


def _sniffed_texts(top: str, entries: list[tuple[str, str]]) -> dict[str, str]:
    """The start (SNIFF_BYTES) of the staged text of each (name, object id) whose name leaves
    it open whether it is a shader: what the content sniff reads, without writing any file. A
    blob over MAX_FILE_BYTES is no student's tab file: left out (so not taken as a shader)."""
    from ..shadertoy.sources import MAX_FILE_BYTES, SNIFF_BYTES, name_says_shader

    wanted = [(name, oid) for name, oid in entries if name_says_shader(name) is None]
    if not wanted:
        return {}
    ids = "".join(f"{oid}\n" for _, oid in wanted).encode()
    sizes = _git("cat-file", "--batch-check=%(objectsize)", cwd=top, stdin=ids).split()
    small = [(n, oid) for (n, oid), size in zip(wanted, sizes) if int(size) <= MAX_FILE_BYTES]
    out = _git("cat-file", "--batch", cwd=top, stdin="".join(f"{o}\n" for _, o in small).encode())
    texts: dict[str, str] = {}
    at = 0
    for name, _ in small:  # "<id> <type> <size>\n<content>\n" per object, in order
        header_end = out.index(b"\n", at)
        size = int(out[at:header_end].split()[2])
        body = out[header_end + 1 : header_end + 1 + size]
        texts[name] = body[:SNIFF_BYTES].decode("utf-8", "replace")
        at = header_end + 1 + size + 1
    return texts


def _checkout(top: str, folder: str, names: list[str]) -> None:
    if names:
        listing = b"".join(os.fsencode(n) + b"\0" for n in names)
        _git("checkout-index", "-z", "--stdin", f"--prefix={folder}/", cwd=top, stdin=listing)


@contextlib.contextmanager
def staged_checkout(
    skipped: list[tuple[str, str]] | None = None, passed_over: list[str] | None = None
) -> Iterator[list[str]]:
    """Write the staged shader files (and their context) into a temporary folder, enter it, and
    yield their names (relative to it and to the top of the work tree); cwd and the folder are
    restored and removed afterwards. InputError outside a git work tree. `skipped` (when given)
    receives (name, what it is) for each staged symbolic link or submodule named as a shader;
    `passed_over` (when given) the staged files that are not shader files."""
    try:
        top = os.fsdecode(_git("rev-parse", "--show-toplevel").rstrip(b"\n"))
    except InputError:
        raise InputError("glslcheck lint --staged: error: not inside a git work tree") from None
    entries = staged_entries(top)
    staged = [name for mode, _, name in entries if _is_regular(mode)]
    others = [
        (name, NOT_FILES.get(mode, f"mode {mode}"))
        for mode, _, name in entries
        if not _is_regular(mode)
    ]
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
        texts = _sniffed_texts(top, [(n, oid) for mode, oid, n in entries if _is_regular(mode)])
        shaders = _shader_names(staged, texts)
        if passed_over is not None:
            taken = set(shaders)
            passed_over.extend(name for name in staged if name not in taken)
        if skipped is not None:
            named = set(_shader_names([name for name, _ in others]))
            skipped.extend((name, what) for name, what in others if name in named)
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
