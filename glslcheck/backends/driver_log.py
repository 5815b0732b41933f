"""A GL driver's compile log read as diagnostics in the user's files: the log's formats (Mesa's,
glslang's, NVIDIA's), `#line` renumbering, Mesa's columns, and where mainImage is when the
wrapper is to blame. The GL backend (llvmpipe) and the WebGL backend (Chromium's ANGLE, whose
translator reports as glslang does) read their drivers' logs with it."""

from __future__ import annotations

import re

from ..base.diagnostics import Diagnostic, Location, source_line

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ..shadertoy.wrapper import Program

RULE = "gl-compile"

# Mesa: "0:42(5): error: `y' undeclared", "0:3(1): preprocessor error: #error boom";
# other drivers: "ERROR: 0:42: ..." or "0(42) : error ...".
_MESA_RE = re.compile(
    r"^\s*(\d+):(\d+)\((\d+)\):\s*(?:preprocessor\s+)?(error|warning):\s*(.*)$", re.I
)
_GLSLANG_STYLE_RE = re.compile(r"^\s*(ERROR|WARNING):\s*(\d+):(\d+):\s*(.*)$", re.I)
_NVIDIA_RE = re.compile(r"^\s*(\d+)\((\d+)\)\s*:\s*(error|warning)\s*\w*:\s*(.*)$", re.I)


def parse_driver_log(log: str) -> list[tuple[int | None, int | None, str, str]]:
    """(program line, column, severity, message) for each message in a driver's compile/link log.

    Lines that carry no position but say "error" (linker messages) come back with line None.
    The line is the driver's, which a `#line` directive renumbers (see `_driver_entries`).
    """
    return [entry[1:] for entry in _driver_entries(log)]


def _driver_entries(log: str) -> list[tuple[int, int | None, int | None, str, str]]:
    """(source string number, line, column, severity, message), as parse_driver_log."""
    out: list[tuple[int, int | None, int | None, str, str]] = []
    for raw in log.splitlines():
        if m := _MESA_RE.match(raw):
            out.append((int(m[1]), int(m[2]), int(m[3]), m[4].lower(), m[5].strip()))
        elif m := _GLSLANG_STYLE_RE.match(raw):
            out.append((int(m[2]), int(m[3]), None, m[1].lower(), m[4].strip()))
        elif m := _NVIDIA_RE.match(raw):
            out.append((int(m[1]), int(m[2]), None, m[3].lower(), m[4].strip()))
        elif (
            re.search(r"\berror\b", raw, re.I)
            and "Compiler failed" not in raw
            and "Linker failed" not in raw
        ):
            out.append((0, None, None, "error", raw.strip()))
    return out


_LINE_DIRECTIVE_RE = re.compile(r"^[ \t]*#[ \t]*line[ \t]+(\w+)(?:[ \t]+(\w+))?[ \t]*(?://.*)?$")


def _c_integer(text: str | None) -> int | None:
    """A C integer literal (decimal, 0x hex, 0 octal) or None."""
    if text is None or not re.fullmatch(r"0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*", text):
        return None
    return (
        int(text, 16)
        if text[:2].lower() == "0x"
        else int(text, 8)
        if text.startswith("0")
        else int(text)
    )


def driver_line_map(text: str) -> dict[tuple[int | None, int], list[int]]:
    """The program line the driver means by (source string number, line) after `#line`s.

    `#line N [S]` makes the next line line N (of source string S); GLSL ES 3.00 section 3.4.
    Mesa (22) prints source string 0 whatever S says, so each line is also keyed (None, line),
    for a lookup that ignores the source number. Where `#line` makes lines share a number, all
    are listed in program order (the caller prefers one in the user's text over the wrapper's). A
    `#line` whose arguments are not integer literals (macros, expressions) stops the map: the lines
    after it are left out, and their errors fall back to the location of mainImage.
    """
    mapping: dict[tuple[int | None, int], list[int]] = {}
    source, number = 0, 1
    for program_line, line in enumerate(text.split("\n"), start=1):
        mapping.setdefault((source, number), []).append(program_line)
        if source:
            mapping.setdefault((None, number), []).append(program_line)
        number += 1
        if "line" in line and (m := _LINE_DIRECTIVE_RE.match(line)):
            new_line, new_source = _c_integer(m[1]), _c_integer(m[2]) if m[2] else source
            if new_line is None or new_source is None:
                break
            source, number = new_source, new_line
    return mapping


def mesa_column(line_text: str, column: int) -> int:
    """The real 1-based column for Mesa's `column`: its lexer counts a run of blanks as one
    column."""
    counter, pos = 1, 0
    while pos < len(line_text) and counter < column:
        if line_text[pos] in " \t":
            while pos < len(line_text) and line_text[pos] in " \t":
                pos += 1
        else:
            pos += 1
        counter += 1
    return pos + 1


def driver_diagnostics(program: Program, log: str) -> list[Diagnostic]:
    """The errors in a driver log as diagnostics in the user's files (warnings are dropped).

    A position inside Shadertoy's prelude or footer (e.g. a missing `mainImage`) has no user
    location; the message then says which line of the wrapper it was.
    """
    diags: list[Diagnostic] = []
    lines = program.text.split("\n")
    renumbered = driver_line_map(program.text)
    for source, reported, column, severity, message in _driver_entries(log):
        if severity != "error":
            continue
        line, where = _program_line(program, renumbered, source, reported)
        if where is None:
            if line is not None:
                message += f" (line {line} of the Shadertoy wrapper around the {program.tab} tab)"
            help_ = (
                "the Image tab must define `void mainImage(out vec4 fragColor, "
                "in vec2 fragCoord)`, "
                "with both parameters named"
                if "mainImage" in message
                else None
            )
            # The wrapper's only link to the user's text is its call of mainImage: point there.
            diags.append(Diagnostic(message, entry_location(program), rule=RULE, help=help_))
        else:
            path, user_line = where
            column = mesa_column(lines[line - 1], column) if column and line <= len(lines) else 1
            diags.append(Diagnostic(message, Location(path, user_line, column), rule=RULE))
    if not diags:  # a failure we could not parse: keep the log visible rather than lose it
        diags.append(
            Diagnostic(
                f"the OpenGL driver rejected the {program.tab} program:\n{log.strip()}",
                None,
                rule=RULE,
            )
        )
    return diags


def _program_line(program: Program, renumbered: dict, source: int, reported: int | None):
    """(program line, user location or None) of a driver's (source, line): the first candidate
    in the user's text, else the first one at all (see driver_line_map)."""
    if reported is None:
        return None, None
    candidates = renumbered.get((source, reported), []) + renumbered.get((None, reported), [])
    for line in candidates:
        if (where := program.locate(line)) is not None:
            return line, where
    return (candidates[0] if candidates else None), None


def entry_location(program: Program) -> Location | None:
    """Where the user's tab defines mainImage (or, failing that, the tab file's first line)."""
    tab_paths = [seg.path for seg in program.segments]
    if not tab_paths:
        return None
    for path in reversed(tab_paths):  # the pass's own tab comes after Common
        for number in range(1, 100_000):
            text = source_line(path, number)
            if text is None:
                break
            m = re.search(r"\bmainImage\s*\(", text)
            if m:
                return Location(
                    path, number, m.start() + 1, number, m.start() + len("mainImage") + 1
                )
    return Location(tab_paths[-1], 1, 1)
