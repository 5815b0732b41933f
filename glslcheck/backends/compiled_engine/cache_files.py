"""The compiled engine's files beside numba's cache (generated modules, their markers, the tier
records): where they live, and writing and reading them whole."""

from __future__ import annotations

import os

from ..cpu_core import numba_cache


def folder() -> str:
    """The folder of the compiled modules, beside numba's cache."""
    return os.path.join(numba_cache.trusted_dir(), "compiled")


def write(path: str, text: str, quiet: bool = True) -> None:
    """A file of the cache, atomically (a reader sees all of it or none); `quiet`: a read-only
    cache is no error (a record not kept)."""
    try:
        os.makedirs(os.path.dirname(path), mode=0o700, exist_ok=True)
        tmp = f"{path}.{os.getpid()}"
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except OSError:
        if not quiet:
            raise


def read(path: str, strip: bool = True) -> str | None:
    try:
        with open(path) as f:
            text = f.read()
    except OSError:
        return None
    return text.strip() if strip else text


def cached(folder: str, key: str) -> bool:
    """Whether numba had machine code for the whole module before this load: the index file of
    render_rows, which numba compiles and caches last (a compile stopped halfway leaves some of
    the functions it calls)."""
    head = f"m{key}.render_rows-"
    return any(n.startswith(head) and n.endswith(".nbi") for n in _listdir(folder))


def _listdir(folder: str) -> list[str]:
    out = []
    for root, _, files in os.walk(folder):
        out += files
    return out
