"""glslcheck/base/regexes.py: the lint path's regular expressions compiled ahead of time (so
start-up does not pay for compiling them). The stored programs must be the ones this interpreter's
`re` makes for exactly the patterns the lint path compiles, and a pattern made from them must be the
same `re.Pattern`."""

from __future__ import annotations

import os
import re

import pytest

from glslcheck.base import _regex_code, regexes


def test_the_file_holds_every_pattern_the_lint_path_compiles():
    """A pattern added, changed or dropped on the lint path fails here until
    `python -m glslcheck.base.regexes` writes glslcheck/base/_regex_code.py again."""
    assert sorted(_regex_code.CODE) == regexes.lint_path_patterns()


def test_the_stored_programs_are_this_interpreters():
    """On the interpreter that wrote the file (the fingerprint: version and `_sre.MAGIC`), each
    stored program is what `re` compiles the pattern to; on another, `compiled` uses `re.compile`
    (tested below), so the file is only ever read where it was written. Another interpreter on a
    developer's machine is a skip (lint stays correct there, only slower to start); on CI, whose
    interpreter is the one the project is set up with (make setup), it is a failure: the file is
    stale and start-up would lose its stored programs unnoticed."""
    if _regex_code.FINGERPRINT != regexes.fingerprint():
        why = (
            f"glslcheck/base/_regex_code.py was written by {_regex_code.FINGERPRINT}, this is "
            f"{regexes.fingerprint()}: run `python -m glslcheck.base.regexes`"
        )
        if os.environ.get("CI"):
            pytest.fail(why)
        pytest.skip(why + " (this interpreter compiles with re; CI fails instead)")
    for (pattern, flags), stored in _regex_code.CODE.items():
        assert regexes.program(pattern, flags) == stored, pattern


# A few of the stored patterns with texts they match and texts they do not.
SAMPLES = [
    "// Image.glsl - draws the lit spheres\n// Authors: Ada Lovelace (lighting), Alan Turing\n",
    "  /* glslcheck: ignore[missing-header] */ code();",
    "#ifdef FOO\n#if defined(BAR)\nfloat x = 1.5e3f + 0x1Fu;",
    "Code by Dan Buckstein",
    "// part 3",
    "// TEST",
    "-----",
    "ſ KELVIN K \u212a ß ǅ",
    "void main(void) { }",
    "#version 300 es",
    "based on the starter framework",
]


@pytest.mark.parametrize("key", sorted(_regex_code.CODE), ids=lambda key: key[0][:40])
def test_a_stored_pattern_is_the_pattern_re_compiles(key):
    pattern, flags = key
    ours, theirs = regexes.compiled(pattern, flags), re.compile(pattern, flags)
    assert (ours.pattern, ours.flags, ours.groups, ours.groupindex) == (
        theirs.pattern,
        theirs.flags,
        theirs.groups,
        theirs.groupindex,
    )
    for text in SAMPLES:
        assert [m.span() + m.groups() for m in ours.finditer(text)] == [
            m.span() + m.groups() for m in theirs.finditer(text)
        ]
        assert ours.sub("#", text) == theirs.sub("#", text)


def test_another_interpreter_or_an_unknown_pattern_compiles_with_re(monkeypatch):
    pattern, flags = next(iter(_regex_code.CODE))
    monkeypatch.setattr(regexes, "_table", None)
    monkeypatch.setattr(regexes, "fingerprint", lambda: ("another-python",))
    assert regexes._stored() == {}
    assert regexes.compiled(pattern, flags).pattern == pattern
    assert regexes.compiled(r"not (stored)", re.I).groups == 1
