"""The lint path's regular expressions, compiled ahead of time as the interpreter compiles
modules ahead of time into .pyc files, for start-up time.

Python's `re` parses and compiles every pattern in Python at each start, and the patterns a
`glslcheck lint FILE` compiles (the lexer's, the preprocessor's, the text scan's, the header and
comment rules' word lists) are a noticeable share of its start-up. `re.compile`
ends by handing the compiled program (a list of integers) to `_sre.compile`, CPython's
internal constructor of a `re.Pattern`; `base/_regex_code.py` holds those programs, written by

    python -m glslcheck.base.regexes

for the patterns the lint path asks for, with the fingerprint of the interpreter whose `re`
wrote them (its version, `_sre.MAGIC`: the engine's code format, its word size and byte
order). `compiled(pattern, flags)` gives `_sre.compile` the stored program when the running
interpreter has that fingerprint, and is `re.compile(pattern, flags)` otherwise (another Python
version or implementation, a pattern not in the file): the same `re.Pattern` either way, and
`_sre.compile` checks every program it is given. tests/test_regexes.py checks that the file
holds exactly the patterns the lint path compiles and that each stored program is the one this
interpreter's `re` makes, so a changed pattern fails the tests until the file is written again.
"""

from __future__ import annotations

import re
import sys

try:
    import _sre
except ImportError:  # another implementation: `re.compile` only
    _sre = None


_table: dict | None = None
# (pattern, flags) of every call, while `record` runs (the generator's list of patterns).
_recorded: list[tuple[str, int]] | None = None


def fingerprint() -> tuple:
    """What the stored programs depend on: the interpreter and its regular-expression engine."""
    if _sre is None:
        return (sys.implementation.name,)
    return (
        sys.implementation.name,
        sys.version_info[:2],
        _sre.MAGIC,
        _sre.CODESIZE,
        _sre.MAXREPEAT,
        _sre.MAXGROUPS,
        sys.maxunicode,
        sys.byteorder,
        memoryview(b"").cast("I").itemsize,
    )


def _stored() -> dict:
    global _table
    if _table is None:
        _table = {}
        try:
            from . import _regex_code
        except ImportError:
            pass
        else:
            if _regex_code.FINGERPRINT == fingerprint():
                _table = _regex_code.CODE
    return _table


def compiled(pattern: str, flags: int = 0) -> re.Pattern:
    """`re.compile(pattern, flags)`, from the stored program when there is one for this
    interpreter."""
    flags = int(flags)
    if _recorded is not None:
        _recorded.append((pattern, flags))
    entry = _stored().get((pattern, flags))
    if entry is None:
        return re.compile(pattern, flags)
    final_flags, code, groups, names = entry
    indexgroup = [None] * (groups + 1)
    for name, index in names:
        indexgroup[index] = name
    return _sre.compile(
        pattern,
        final_flags,
        memoryview(code).cast("I").tolist(),
        groups,
        dict(names),
        tuple(indexgroup),
    )


def program(pattern: str, flags: int) -> tuple:
    """What `re.compile(pattern, flags)` hands `_sre.compile`, as `_regex_code.CODE` stores it:
    (flags with the pattern's inline ones, the program, the number of groups, (name, index) of
    each named group)."""
    import re._compiler as _compiler
    import re._parser as _parser

    parsed = _parser.parse(pattern, flags)
    code = _compiler._code(parsed, flags)
    names = tuple(sorted(parsed.state.groupdict.items(), key=lambda item: item[1]))
    # The program as the bytes of its native 32-bit words (`_sre.CODESIZE` 4, in the fingerprint
    # with the byte order): one bytes literal compiles in a moment when no .pyc can be written,
    # where a tuple of thousands of numbers took more than the patterns themselves.
    words = memoryview(bytearray(4 * len(code))).cast("I")
    for i, c in enumerate(code):
        words[i] = c
    return (int(flags | parsed.state.flags), words.tobytes(), parsed.state.groups - 1, names)


def lint_path_patterns() -> list[tuple[str, int]]:
    """Every (pattern, flags) the lint path compiles through `compiled` when it starts: its
    modules imported, the parser's tables loaded and every rule loaded, in a fresh interpreter
    (the patterns are module constants: compiled once, at import)."""
    import json
    import subprocess

    script = (
        "import json, sys; from glslcheck.base import regexes; regexes._recorded = []; "
        "regexes._table = {}\n"
        "from glslcheck.frontend import parser as parse; from glslcheck.cli import main as cli\n"
        "from glslcheck.cli.commands import lint as _lint_command\n"
        "from glslcheck.lint import engine, recover, report; from glslcheck.lint.rules import "
        "all_rules\n"
        "parse.get_parser(); all_rules()\n"
        "print(json.dumps(regexes._recorded))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    )
    return sorted({(p, f) for p, f in json.loads(done.stdout)})


def source(patterns: list[tuple[str, int]]) -> str:
    """The text of `base/_regex_code.py` for `patterns`, compiled by this interpreter."""
    lines = [
        '"""The compiled programs of the lint path\'s regular expressions (see '
        "glslcheck/base/regexes.py).",
        "",
        "Written by `python -m glslcheck.base.regexes`; do not edit.",
        '"""',
        "",
        f"FINGERPRINT = {fingerprint()!r}",
        "",
        "CODE = {",
    ]
    for pattern, flags in patterns:
        lines.append(f"    ({pattern!r}, {flags!r}): {program(pattern, flags)!r},")
    lines.append("}")
    return "\n".join(lines) + "\n"


def main() -> int:
    from .generated import write_base_module

    write_base_module("_regex_code.py", source(lint_path_patterns()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
