"""Files that glslcheck's own tools generate (parser tables, precompiled start-up code), each
replaced in one step so a reader never sees half of it."""

from __future__ import annotations

import os


def write_generated(path: str, text: str) -> None:
    """Replace the generated file `path` with `text` atomically and say so."""
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)
    print(f"wrote {path}")


def write_base_module(name: str, text: str) -> None:
    """`write_generated` for a module of this package (`_regex_code.py`, `_init_code.py`)."""
    write_generated(os.path.join(os.path.dirname(os.path.abspath(__file__)), name), text)
