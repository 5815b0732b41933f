"""The reference compiler: glslangValidator (Debian package glslang-tools) run on whole programs.

This module owns calling glslangValidator and reading its output. `validate` checks one program
text and returns the errors with program line numbers; `validate_shader` checks every pass of a
Shadertoy shader the way Shadertoy compiles it (Common alone, then Common + each pass tab, see
`glslcheck.shadertoy.wrapper`) and maps each error back to the user's file and line.

glslangValidator prints errors as `ERROR: 0:LINE: 'token' : message` (string 0, since we pass
one file) and ends with a summary line such as `ERROR: 2 compilation errors.  No code generated.`;
it exits 0 when the program compiles.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field

from ..base.diagnostics import Diagnostic, InputError, Location
from ..shadertoy.sources import Shader
from ..shadertoy.wrapper import PASS_TABS, Program, build_common_only, build_program

EXECUTABLE = "glslangValidator"
TIMEOUT_SECONDS = 30

# "ERROR: 0:12: 'x' : undeclared identifier" / "WARNING: 0:3: ..."; LINE may be missing.
_MESSAGE_RE = re.compile(r"^(ERROR|WARNING): (?:(\d+):(\d+): )?(.*)$")
# Lines glslang adds after the real errors; they say nothing about the shader.
_NOISE_RE = re.compile(r"compilation terminated|\d+ compilation errors?\.|No code generated")


class GlslangUnavailable(InputError):
    """glslangValidator is not installed (an environment problem: exit 2)."""


@dataclass(slots=True)
class Result:
    """What glslangValidator said about one program: errors as (program line or None, message)."""

    ok: bool
    messages: list[tuple[int | None, str]] = field(default_factory=list)
    raw: str = ""
    warnings: list[tuple[int | None, str]] = field(default_factory=list)


def glslang_path() -> str | None:
    """The glslangValidator executable on PATH, or None."""
    return shutil.which(EXECUTABLE)


def _clean(message: str) -> str:
    """`'=' :  cannot convert from ' const int' to ' temp highp float'` -> single spaces, no `''
    :`."""
    message = re.sub(r"^'' :\s*", "", message)
    message = re.sub(r"' (const|temp|uniform|in|out|inout) ", r"'\1 ", message)
    return re.sub(r"\s{2,}", " ", message).strip()


def parse_output(raw: str) -> tuple[list[tuple[int | None, str]], list[tuple[int | None, str]]]:
    """Errors and warnings from glslangValidator's output, noise lines dropped."""
    errors: list[tuple[int | None, str]] = []
    warnings: list[tuple[int | None, str]] = []
    for line in raw.splitlines():
        m = _MESSAGE_RE.match(line.strip())
        if not m:
            continue
        kind, _string, lineno, message = m.groups()
        if _NOISE_RE.search(message):
            continue
        entry = (int(lineno) if lineno else None, _clean(message))
        (errors if kind == "ERROR" else warnings).append(entry)
    return errors, warnings


def validate(text: str, stage: str = "frag") -> Result:
    """Compile `text` as one `stage` shader ("frag", "vert", ...) with glslangValidator."""
    exe = glslang_path()
    if exe is None:
        raise GlslangUnavailable(
            f"error: {EXECUTABLE} not found on PATH; install the Debian package glslang-tools "
            "(sudo apt-get install glslang-tools)"
        )
    fd, path = tempfile.mkstemp(suffix=f".{stage}", prefix="glslcheck-")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        proc = subprocess.run(
            [exe, path], capture_output=True, text=True, errors="replace", timeout=TIMEOUT_SECONDS
        )
    except subprocess.TimeoutExpired:
        raise InputError(f"error: {EXECUTABLE} took more than {TIMEOUT_SECONDS} s") from None
    finally:
        os.unlink(path)
    raw = (proc.stdout + proc.stderr).replace(path, "<program>")
    errors, warnings = parse_output(raw)
    ok = proc.returncode == 0
    if not ok and not errors:  # a failure we could not parse: keep it visible
        errors = [(None, raw.strip() or f"{EXECUTABLE} exited with status {proc.returncode}")]
    return Result(ok, errors, raw, warnings)


def diagnostics_for(program: Program, result: Result, rule: str = "glslang") -> list[Diagnostic]:
    """The errors of `result` as diagnostics located in the user's files via `program.locate`."""
    out: list[Diagnostic] = []
    for line, message in result.messages:
        where = program.locate(line) if line is not None else None
        if where is None:
            note = (
                f" (line {line} of the Shadertoy wrapper for the {program.tab} tab)" if line else ""
            )
            out.append(Diagnostic(message + note, None, rule=rule))
        else:
            path, user_line = where
            out.append(Diagnostic(message, Location(path, user_line, 1), rule=rule))
    return out


def validate_shader(shader: Shader) -> list[Diagnostic]:
    """Compile each pass as Shadertoy does and return glslang's errors located in the user's files.

    Common is compiled alone first (only iDate/iSampleRate declared), then Common + each pass tab
    present (Buffer A..D, Image) or the plain GLSL file. An error in Common shows up in several
    programs; it is reported once.
    """
    programs: list[Program] = []
    if shader.common is not None:
        programs.append(build_common_only(shader))
    for tab in (*PASS_TABS, "GLSL"):
        if tab in shader.tabs:
            programs.append(build_program(shader, tab))
    seen: set[tuple[str, int, str]] = set()
    out: list[Diagnostic] = []
    for program in programs:
        for d in diagnostics_for(program, validate(program.text)):
            key = (d.loc.path if d.loc else program.tab, d.loc.line if d.loc else 0, d.message)
            if key not in seen:
                seen.add(key)
                out.append(d)
    return out
