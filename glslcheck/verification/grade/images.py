"""`glslcheck grade --images FOLDER`: every render and diff image of the class as PNG files, so
the CSV and JSON can point at them: `<team>-t<i>.png`, `<team>-t<i>-diff.png` and
`reference-t<i>.png` (i: the index of the time in --times). Each file is written atomically;
the files' names are kept in `Grade.images` (frame index and kind -> path)."""

from __future__ import annotations

import os
import re

from ...base.diagnostics import InputError
from ...base.images import atomic_write, png_bytes, thumbnail
from .grading import Reference
from .records import Grade

_UNSAFE = re.compile(r"[^A-Za-z0-9._-]+")


def file_stem(team: str) -> str:
    """A team's name as a file name: letters, digits, `.`, `_` and `-` kept, the rest `_`."""
    return _UNSAFE.sub("_", team).strip("._") or "team"


def _write(path: str, data: bytes) -> None:
    with atomic_write(path, "image") as tmp, open(tmp, "wb") as f:
        f.write(data)


def write_images(grades: list[Grade], reference: Reference | None, folder: str) -> None:
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as e:
        raise InputError(f"{folder}: error: cannot make the folder ({e.strerror or e})") from None
    if reference is not None:
        for i, img in enumerate(reference.images):
            _write(
                os.path.join(folder, f"reference-t{i}.png"), png_bytes(thumbnail(img, img.shape[1]))
            )
    used: set[str] = set()
    for g in grades:
        stem = file_stem(g.team)
        while stem in used:  # two names that differ only in unsafe characters
            stem += "_"
        used.add(stem)
        for i, f in enumerate(g.frames):
            for kind, data in (("render", f.render), ("diff", f.diff)):
                if not data:
                    continue
                name = f"{stem}-t{i}.png" if kind == "render" else f"{stem}-t{i}-diff.png"
                path = os.path.join(folder, name)
                _write(path, data)
                g.images[f"{i}:{kind}"] = path
