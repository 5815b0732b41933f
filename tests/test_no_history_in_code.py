"""Comments, docstrings and test names say what the code does and why, not the work log that led
to it: no issue, session or stop number (the word followed by a number) in the Python files of
glslcheck/, tests/, tools/ and benchmarks/. The history lives in git, the issues and docs/. The
whole text of each file is read, which is stricter than comments and docstrings alone and needs
no tokenizer. Only .py files are read: the shaders and other test data are not code."""

from __future__ import annotations

import os
import re

import glslcheck

ROOT = os.path.dirname(os.path.dirname(glslcheck.__file__))
FOLDERS = ("glslcheck", "tests", "tools", "benchmarks")
# Built from pieces so that this file's own source does not match it.
# A hyphen counts after the issue word too; "stop-1" is arithmetic (start..stop-1), so not there.
HISTORY = re.compile(
    r"\b(?:" + "issu" + r"es?[\s-]+|(?:" + "sess" + "ion|" + "st" + r"op)\s+)#?[0-9]+",
    re.IGNORECASE,
)


def _python_files() -> list[str]:
    out = []
    for name in FOLDERS:
        for folder, dirs, files in os.walk(os.path.join(ROOT, name)):
            dirs[:] = [d for d in dirs if d != "__pycache__" and not d.startswith(".")]
            out.extend(os.path.join(folder, f) for f in files if f.endswith(".py"))
    return sorted(out)


def test_the_scan_covers_every_folder():
    files = _python_files()
    for name in FOLDERS:
        assert any(os.path.relpath(f, ROOT).startswith(name + os.sep) for f in files), name
    assert os.path.abspath(__file__) in map(os.path.abspath, files)


def test_no_issue_or_session_numbers_in_code_tests_tools_or_benchmarks():
    found = []
    for path in _python_files():
        with open(path, encoding="utf-8") as f:
            text = f.read()
        where = os.path.relpath(path, ROOT)
        for match in HISTORY.finditer(text):  # the whole text: a docstring may wrap the number
            number = text.count("\n", 0, match.start()) + 1
            found.append(f"{where}:{number}: {' '.join(match.group(0).split())}")
    assert not found, f"{len(found)} references to the work log:\n" + "\n".join(found)
