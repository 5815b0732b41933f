"""Whether numba is installed, and where it keeps its compiled machine code for glslcheck, set
before anything compiles: what both CPU engines need of numba before they import it.

Its own module, imported by the NumPy engine (numpy_engine/jit.py and jit_kernels.py) and the
compiled engine (engine.py, scalar.py, lanes_math.py, texture_kernels.py), so that a module of
kernels can set the directory at its import without importing the code that loads it.

The folder holds what runs as code: numba unpickles its index files, and the compiled engine
runs the modules it finds there. So it is used only when no other user can write it or swap
it (:func:`trusted_dir`); otherwise a private temporary folder serves this process.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import stat
import sys

_TRUSTED: dict[str, str] = {}  # wanted folder -> the folder used for it (itself or a private one)


@functools.lru_cache(maxsize=1)
def installed() -> bool:
    """Whether numba is installed (the optional extra `glslcheck[jit]`), without importing it."""
    return importlib.util.find_spec("numba") is not None


def cache_dir() -> str:
    """Where numba keeps the compiled kernels: $NUMBA_CACHE_DIR, else the user's cache."""
    given = os.environ.get("NUMBA_CACHE_DIR")
    if given:
        return given
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "glslcheck", "numba")


def unsafe_reason(path: str) -> str | None:
    """Why another user could plant files in the folder `path` (which exists), or None.

    The rule of OpenSSH's safe_path: the folder is ours and written by no one else, and every
    folder above it belongs to us or to root and is written by no one else unless sticky (so
    /tmp may hold it, but nobody can rename it away and put their own in its place)."""
    if not hasattr(os, "getuid"):
        return None
    uid = os.getuid()
    real = os.path.realpath(path)
    st = os.stat(real)
    if st.st_uid != uid:
        return f"belongs to another user (uid {st.st_uid})"
    if st.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        return "can be written by other users"
    parent = os.path.dirname(real)
    while True:
        st = os.stat(parent)
        if st.st_uid not in (0, uid):
            return f"is inside {parent}, which belongs to another user (uid {st.st_uid})"
        if st.st_mode & (stat.S_IWGRP | stat.S_IWOTH) and not st.st_mode & stat.S_ISVTX:
            return f"is inside {parent}, which other users can write"
        if parent == os.path.dirname(parent):
            return None
        parent = os.path.dirname(parent)


def trusted_dir() -> str:
    """:func:`cache_dir`, made (mode 0700) when missing, if no other user can write it; else a
    private temporary folder for this process, with a warning naming the folder and why."""
    wanted = cache_dir()
    used = _TRUSTED.get(wanted)
    if used is None:
        try:
            os.makedirs(wanted, mode=0o700, exist_ok=True)
            reason = unsafe_reason(wanted)
        except OSError as e:
            reason = f"cannot be made or read ({e.strerror or e})"
        used = wanted
        if reason is not None:
            import atexit
            import shutil
            import tempfile

            used = tempfile.mkdtemp(prefix="glslcheck-numba-")
            atexit.register(shutil.rmtree, used, True)
            print(
                f"glslcheck: warning: the numba cache folder {wanted} {reason}; compiling into a "
                f"private folder for this run instead (set NUMBA_CACHE_DIR to a folder only you "
                f"can write)",
                file=sys.stderr,
            )
        _TRUSTED[wanted] = _TRUSTED[used] = used
    return used


def use_cache_dir() -> str:
    """Point numba's cache at :func:`trusted_dir` (before any function is compiled) and return it.

    ``$NUMBA_CACHE_DIR`` is set when missing, for numba's import; if numba was imported already,
    its config is reloaded at once, every other setting kept as it is. numba re-reads its whole
    config from the environment at the start of a compile whenever a ``NUMBA_`` variable changed
    since it last looked (CompilerBase calls config.reload_config), which would undo what was
    assigned to numba.core.config meanwhile (the lockstep engine's ``SLP_VECTORIZE = 1``)."""
    path = trusted_dir()
    changed = os.environ.get("NUMBA_CACHE_DIR") != path
    os.environ["NUMBA_CACHE_DIR"] = path
    if "numba" in sys.modules:
        from numba.core import config

        if changed:
            kept = {k: getattr(config, k) for k in dir(config) if k.isupper() and k != "CACHE_DIR"}
            config.reload_config()  # takes the environment's snapshot now, so no compile reloads it
            for k, v in kept.items():
                setattr(config, k, v)
        config.CACHE_DIR = path
    return path
