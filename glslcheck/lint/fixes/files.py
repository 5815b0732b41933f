"""Shader files as fixes read and write them: the bytes on disk, the text lint saw, and back.

Lint reads a file as UTF-8 with its byte-order mark dropped and every line ending made `\\n`
(`shadertoy.sources.decode`); fixes edit that text. Writing it back keeps what the file had: its
byte-order mark and, line by line, its line endings (a line a fix added takes the ending most
of the file's lines have). A file is written only when it still holds the bytes it was read
with, through a temporary file renamed over it (its mode kept): a file that changed on disk
since is left alone.
"""

from __future__ import annotations

import os
import re

from ...base.diagnostics import InputError
from ...base.records import record
from ...shadertoy.sources import decode
from .edits import line_map

BOM = b"\xef\xbb\xbf"
_ENDING = re.compile(r"\r\n|\r|\n")


@record(frozen=True)
class FileText:
    """One shader file as read: its bytes and the text lint sees."""

    path: str
    data: bytes
    text: str


def read_file(path: str) -> FileText:
    """The file's bytes and text; InputError when it cannot be read or is not UTF-8."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise InputError(f"{path}: error: cannot read the file ({e.strerror})") from None
    return FileText(path, data, decode(data, path))


def _endings(data: bytes) -> list[str]:
    """The line ending after each line of the file (index 0: line 1; the last line's is "" when
    the file does not end with one)."""
    raw = data[len(BOM) :] if data.startswith(BOM) else data
    text = raw.decode("utf-8")
    found = [m.group(0) for m in _ENDING.finditer(text)]
    return [*found, ""]


def to_bytes(original: FileText, new_text: str) -> bytes:
    """`new_text` (lines ending in `\\n`) as the file's bytes: its BOM and line endings kept."""
    endings = _endings(original.data)
    counts: dict[str, int] = {}
    for e in endings[:-1]:
        counts[e] = counts.get(e, 0) + 1
    usual = max(counts, key=lambda e: counts[e]) if counts else "\n"
    mapped = line_map(original.text, new_text)
    parts = new_text.split("\n")
    out: list[str] = []
    for j, part in enumerate(parts, start=1):
        out.append(part)
        if j == len(parts):
            break
        old = mapped.get(j)
        ending = endings[old - 1] if old is not None and endings[old - 1] else usual
        out.append(ending)
    data = "".join(out).encode("utf-8")
    return BOM + data if original.data.startswith(BOM) else data


def write_file(original: FileText, new_text: str) -> str | None:
    """Write `new_text` over the file when it still holds the bytes it was read with; None when
    written, else what happened (the file is then left as it is)."""
    try:
        with open(original.path, "rb") as f:
            now = f.read()
    except OSError as e:
        return f"cannot read it again ({e.strerror}); not written"
    if now != original.data:
        return "changed on disk since it was read; left alone (lint it again)"
    from ...base.images import atomic_write  # numpy: only when a file is written

    data = to_bytes(original, new_text)
    try:
        with atomic_write(original.path, "fixed shader") as tmp:
            with open(tmp, "wb") as f:
                f.write(data)
    except InputError as e:  # the folder or file cannot be written: the others still are
        return str(e).split(": error: ", 1)[-1] + "; not written"
    return None


def unified_diff(original: FileText, new_text: str, context: int = 3) -> str:
    """The change as a unified diff of the file's text, both sides named by the path (difflib's
    hunks without its "junk" heuristic, which in a long file leaves a `}` line unmatched)."""
    from difflib import SequenceMatcher

    name = original.path.replace(os.sep, "/")
    a = original.text.splitlines(keepends=True)
    b = new_text.splitlines(keepends=True)
    out = [f"--- {name}\n", f"+++ {name}\n"]
    matcher = SequenceMatcher(None, a, b, autojunk=False)
    for group in matcher.get_grouped_opcodes(context):
        i1, i2, j1, j2 = group[0][1], group[-1][2], group[0][3], group[-1][4]
        out.append(f"@@ -{_range(i1, i2)} +{_range(j1, j2)} @@\n")
        for tag, a1, a2, b1, b2 in group:
            if tag == "equal":
                out.extend(" " + line for line in a[a1:a2])
                continue
            out.extend("-" + line for line in a[a1:a2])
            out.extend("+" + line for line in b[b1:b2])
    return "".join(
        line if line.endswith("\n") else line + "\n\\ No newline at end of file\n" for line in out
    )


def _range(start: int, stop: int) -> str:
    """A hunk's `first,count` (as `diff -u` writes it: `first` is 0 for an empty side)."""
    count = stop - start
    first = start + 1 if count else start
    return f"{first}" if count == 1 else f"{first},{count}"
