"""Syntax-error recovery for the linter: drop the top-level declaration a syntax error is in.

A student's file with one syntax error should still get every finding the rest of it earns.
The LALR parser stops at the first error, so the engine (`program_tree`) asks this module to
take the declaration holding the error out of the user's text and parses again:

* a function definition keeps its prototype (`float f(in vec3 p)` + `;`), so every caller
  still checks; only its body is blanked;
* anything else (a struct, a global, a function whose header is the broken part, a second
  error in a kept prototype) is blanked whole;
* a preprocessor directive with an error is blanked (its line only);
* a word GLSL ES 3.00 reserves used as a name (`float sample(vec2 uv)`, `vec3 filter`) is
  spelt with one letter's case changed (`Sample`) wherever the program uses it, so nothing is
  dropped: the error is reported once, at its first use, and every rule reads the rest.

Blanking replaces characters with spaces and keeps every newline, so every location after the
drop still points at the user's own line and column. Declarations are found on the file's text
with comments and preprocessor lines skipped (a macro body's braces do not count); a
declaration never closed runs to the end of the file and is blanked whole; an error in a file
that is not one of the units gives up (None), and the linter reports the error alone.
"""

from __future__ import annotations

import re

from ..base.diagnostics import Location
from ..base.records import replace
from ..base.regexes import compiled
from ..shadertoy.sources import Source

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

_CALLED_NAME = compiled(r"([A-Za-z_]\w*)\s*\(")  # the name a function header declares


def _code_chars(text: str) -> Iterator[tuple[int, str]]:
    """(offset, char) of the text outside comments and preprocessor lines."""
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
            continue
        if line_start and c == "#":
            j = i
            while True:  # a directive continues over backslash-newlines
                k = text.find("\n", j)
                if k < 0:
                    j = n
                    break
                if text[k - 1] == "\\":
                    j = k + 1
                    continue
                j = k
                break
            i = j
            continue
        if c == "\n":
            line_start = True
        elif not c.isspace():
            line_start = False
        yield i, c
        i += 1


def declarations(text: str) -> list[tuple[int, int, int | None]]:
    """Top-level declarations as (start, end, body_start): [start, end) covers the declaration up
    to its closing `;` or `}`; body_start is the offset of a function body's `{` (else None).
    None when the braces do not balance."""
    out: list[tuple[int, int, int | None]] = []
    depth, start, body = 0, None, None
    for i, c in _code_chars(text):
        if start is None and not c.isspace():
            start, body = i, None
        if c == "{":
            if depth == 0 and body is None and text[start:i].rstrip().endswith(")"):
                body = i
            depth += 1
        elif c == "}":
            depth -= 1
            if depth < 0:
                return out
            if depth == 0 and body is not None:
                assert start is not None  # a body is found inside a declaration
                out.append((start, i + 1, body))
                start = None
        elif c == ";" and depth == 0 and start is not None:
            out.append((start, i + 1, None))
            start = None
    if start is not None:
        out.append((start, len(text), None))
    return out


def _blank(text: str, a: int, b: int) -> str:
    return text[:a] + re.sub(r"[^\n]", " ", text[a:b]) + text[b:]


def _offset(text: str, line: int, column: int) -> int:
    pos = 0
    for _ in range(line - 1):
        j = text.find("\n", pos)
        if j < 0:
            return len(text)
        pos = j + 1
    return pos + max(column - 1, 0)


def drop_declaration(
    units: list[Source], loc: Location, dropped: list[tuple[str, int, int, str]]
) -> tuple[list[Source], tuple[str, int, int, str] | None]:
    """`units` with the declaration holding `loc` dropped, and the dropped region (path, first
    line, last line, function or declaration name); (units, None) when nothing can be dropped."""
    index = next((i for i, u in enumerate(units) if u.path == loc.path), None)
    if index is None:
        return units, None
    unit = units[index]
    text = unit.text
    lines = text.split("\n")
    if 0 < loc.line <= len(lines) and lines[loc.line - 1].lstrip().startswith("#"):
        # a preprocessor error: drop that directive line (uses of its macro fail where they are)
        start = _offset(text, loc.line, 1)
        new_text = _blank(text, start, start + len(lines[loc.line - 1]))
        if new_text == text:
            return units, None
        new_units = list(units)
        new_units[index] = replace(unit, text=new_text)
        return new_units, (unit.path, loc.line, loc.line, lines[loc.line - 1].strip()[:40])
    at = _offset(text, loc.line, loc.column)
    found = None
    for start, end, body in declarations(text):
        if start <= at < end or (found is None and at < start):
            found = (start, end, body)
            break
    if found is None:
        return units, None
    start, end, body = found
    first = text.count("\n", 0, start) + 1
    last = text.count("\n", 0, end) + 1
    header = text[start:body] if body is not None else text[start:end]
    name_match = _CALLED_NAME.search(header)
    name = name_match.group(1) if name_match else header.split("\n")[0].strip()[:40]
    again = any(p == unit.path and f == first for p, f, _, _ in dropped)
    if body is not None and at >= body and not again:
        new_text = _blank(text, body + 1, end)
        new_text = new_text[:body] + ";" + new_text[body + 1 :]
    else:
        new_text = _blank(text, start, end)
    if new_text == text:
        return units, None
    new_units = list(units)
    new_units[index] = replace(unit, text=new_text)
    return new_units, (unit.path, first, last, name)


_WORD = compiled(r"[A-Za-z_]\w*")
RENAMED = "reserved-word"  # the rule of a reserved word's error that rename_reserved recovered


def rename_reserved(units: list[Source], loc: Location) -> tuple[list[Source], str] | None:
    """`units` with the reserved word at `loc` used as a name renamed in the code of every unit
    (the same length, so every location stays the user's), and the name it is read as; None
    when the error at `loc` is not such a word, or no spelling of it is free."""
    from ..language.builtin_functions import RESERVED_WORDS

    unit = next((u for u in units if u.path == loc.path), None)
    if unit is None:
        return None
    at = _offset(unit.text, loc.line, loc.column)
    found = _WORD.match(unit.text, at)
    word = found.group(0) if found else ""
    if word not in RESERVED_WORDS:
        return None
    used = {m.group(0) for u in units for m in _WORD.finditer(u.text)}
    spellings = (word[:k] + word[k].swapcase() + word[k + 1 :] for k in range(len(word)))
    name = next((n for n in spellings if n not in used and n not in RESERVED_WORDS), None)
    if name is None:
        return None
    out = []
    for u in units:
        code = dict(_code_chars(u.text))
        text = u.text
        for m in reversed(list(_WORD.finditer(text))):
            if m.group(0) == word and m.start() in code:
                text = text[: m.start()] + name + text[m.end() :]
        out.append(replace(u, text=text) if text != u.text else u)
    return out, name
