"""Security: no pickle is ever loaded from a place another local user can write.

The parser used to keep Lark's grammar cache, a pickle, in ~/.cache/glslcheck, and when that
folder could not be created, at a fixed name in the shared temp folder: another user who wrote
that file ran code as whoever ran glslcheck. The tables now ship in the package as JSON
(glslcheck/frontend/parse_tables.py) and nothing is cached at run time.

Each test runs glslcheck in a fresh process whose temp folder and cache folder are planted
with pickles that, when unpickled, create a marker file, at the old names and at names a
cache might use; the cache folder cannot be created (XDG_CACHE_HOME is a file). An audit
hook records every file the process opens under those folders and every unpickled global.
"""

from __future__ import annotations

import json
import os
import pickle
import subprocess
import sys
from pathlib import Path

import pytest

SHADER = (
    "void mainImage(out vec4 fragColor, in vec2 fragCoord) { fragColor = vec4(fragCoord.x / "
    "8.0); }\n"
)

_RUN = r"""
import json, os, sys
opened, unpickled = [], []
watched = [os.path.realpath(p) for p in sys.argv[1:3]]

def hook(event, args):
    if event == "open" and isinstance(args[0], (str, bytes, os.PathLike)):
        path = os.path.realpath(os.fsdecode(args[0]))
        if any(path == w or path.startswith(w + os.sep) for w in watched):
            opened.append(path)
    elif event == "pickle.find_class":
        unpickled.append(f"{args[0]}.{args[1]}")

sys.addaudithook(hook)
from glslcheck.cli.main import main
code = main(sys.argv[3:])
print(json.dumps({"code": code, "opened": opened, "unpickled": unpickled,
                  "pickle_imported": "pickle" in sys.modules}))
"""


class _Plant:
    """Unpickling this creates the marker file (what an attacker's code would do first)."""

    def __init__(self, marker: str) -> None:
        self.marker = marker

    def __reduce__(self):
        return (open, (self.marker, "w"))


def _planted(tmp_path: Path) -> tuple[Path, Path, Path, dict]:
    tmpdir = tmp_path / "shared-tmp"
    home = tmp_path / "home"
    marker = tmp_path / "pwned"
    payload = b"x\n" + pickle.dumps(_Plant(str(marker)))  # Lark's cache: a hash line, then pickles
    version = f"{sys.version_info[0]}{sys.version_info[1]}"
    for folder in (tmpdir, home / ".cache" / "glslcheck"):
        folder.mkdir(parents=True)
        for name in (
            f"glsl-lalr-0.1.0-{version}.cache",
            "glsl-lalr.cache",
            "glslcheck.cache",
            "grammar.pickle",
        ):
            (folder / name).write_bytes(payload)
    blocked = tmp_path / "not-a-folder"
    blocked.write_text("XDG_CACHE_HOME is a file: no cache folder can be made under it\n")
    env = dict(
        os.environ,
        TMPDIR=str(tmpdir),
        TEMP=str(tmpdir),
        TMP=str(tmpdir),
        HOME=str(home),
        XDG_CACHE_HOME=str(blocked),
    )
    return tmpdir, home, marker, env


@pytest.mark.parametrize("command", [["parse"], ["check"], ["lint"], ["transpile", "-o", "{out}"]])
def test_security_no_pickle_is_loaded_from_a_writable_temp_location(tmp_path, command):
    tmpdir, home, marker, env = _planted(tmp_path)
    shader = tmp_path / "Image.glsl"
    shader.write_text(SHADER)
    args = [a.format(out=tmp_path / "out.py") for a in command]
    args = [args[0], str(shader), *args[1:]]
    out = subprocess.run(
        [sys.executable, "-c", _RUN, str(tmpdir), str(home), *args],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    report = json.loads(out.stdout.strip().splitlines()[-1])
    assert report["code"] == (1 if command[0] == "lint" else 0), (
        out.stderr
    )  # lint: findings, no error
    assert not marker.exists(), "a planted pickle was loaded and ran code"
    assert report["unpickled"] == []
    assert report["opened"] == [], f"opened files another user can write: {report['opened']}"
    if command[0] in ("parse", "check", "lint"):
        assert not report["pickle_imported"]  # nothing on these paths can unpickle at all


def test_security_parse_tables_are_not_a_pickle():
    """What the parser loads ships in the package, as a module of plain literals: each statement
    assigns one literal (ast.literal_eval accepts it: no call, no name, no import)."""
    import ast

    from glslcheck.frontend import parse_tables

    path = Path(parse_tables.grammar_folder()) / parse_tables.TABLES_FILE
    tree = ast.parse(path.read_text(encoding="utf-8"))
    assert isinstance(tree.body[0], ast.Expr) and isinstance(
        tree.body[0].value.value, str
    )  # the docstring
    for statement in tree.body[1:]:
        assert isinstance(statement, ast.Assign) and len(statement.targets) == 1, ast.dump(
            statement
        )
        assert isinstance(statement.targets[0], ast.Name)
        ast.literal_eval(statement.value)
