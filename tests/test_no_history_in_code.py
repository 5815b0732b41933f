"""The package's comments and docstrings say what the code does and why, not the work log that
led to it: no `issue 18`, `session 6` or `stop 3` under glslcheck/. The history lives in git,
the issues and docs/. The whole text of each file is read, which is stricter than comments and
docstrings alone and needs no tokenizer."""

from __future__ import annotations

import os
import re

import glslcheck

ROOT = os.path.dirname(glslcheck.__file__)
HISTORY = re.compile(r"\b(?:issues?|session|stop)\s+#?[0-9]+", re.IGNORECASE)


def _python_files() -> list[str]:
    out = []
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        out.extend(os.path.join(folder, f) for f in files if f.endswith(".py"))
    return sorted(out)


def test_no_issue_or_session_numbers_in_the_package():
    found = []
    for path in _python_files():
        with open(path, encoding="utf-8") as f:
            text = f.read()
        where = os.path.relpath(path, os.path.dirname(ROOT))
        for match in HISTORY.finditer(text):  # the whole text: a docstring may wrap "issue\n18"
            number = text.count("\n", 0, match.start()) + 1
            found.append(f"{where}:{number}: {' '.join(match.group(0).split())}")
    assert not found, f"{len(found)} references to the work log:\n" + "\n".join(found)
