"""What lint and check print to a terminal: a shader's text or name never acts on the terminal,
never forges a finding line, and a long line is quoted in a window, not once per finding whole."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from glslcheck.base.diagnostics import MAX_QUOTE, Location, _quote, printable

HEADER = "// Image.glsl: a test shader\n// Contributors: Ada Lovelace: all of it\n\n"


def _glslcheck(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "glslcheck", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        errors="surrogateescape",
        timeout=300,
    )


def test_escape_sequences_in_a_comment_are_shown_not_sent(tmp_path):
    (tmp_path / "Image.glsl").write_text(
        HEADER + "// every pixel\nvoid mainImage(out vec4 c, in vec2 p)\n{\n"
        "    c = vec4(length(p) > 1.0); // \x1b]0;owned\x07\x1b[2J\u202egnp.\n}\n"
    )
    done = _glslcheck("lint", "Image.glsl", cwd=tmp_path)
    assert done.returncode == 1
    assert "length-comparison" in done.stdout
    assert "\x1b" not in done.stdout and "\x07" not in done.stdout and "\u202e" not in done.stdout
    assert "// \\x1b]0;owned\\x07\\x1b[2J\\u202egnp." in done.stdout


def test_a_newline_in_a_file_name_cannot_forge_a_finding(tmp_path):
    name = "Image\nfake.glsl:9:9: missing-header forged finding.glsl"
    (tmp_path / name).write_text("void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n")
    done = _glslcheck("lint", name, cwd=tmp_path)
    assert done.returncode == 1
    assert not any(line.startswith("fake.glsl") for line in done.stdout.splitlines())
    assert (
        "Image\\x0afake.glsl:9:9: missing-header forged finding.glsl:1:1: missing-header"
        in done.stdout
    )


def test_a_one_line_shader_is_quoted_in_a_window(tmp_path):
    body = "c += vec4(length(p) > 1.0);" * 1500  # 40 kB on one line, one finding per statement
    (tmp_path / "Image.glsl").write_text(
        "void mainImage(out vec4 c, in vec2 p) {c = vec4(0.0);" + body + "}\n"
    )
    done = _glslcheck("lint", "Image.glsl", cwd=tmp_path)
    assert done.returncode == 1
    findings = done.stdout.count(": length-comparison")
    assert findings >= 1500
    assert (
        max(len(line) for line in done.stdout.splitlines()) <= 4 + MAX_QUOTE + 6 + 300
    )  # a message line
    assert len(done.stdout) < findings * (2 * (MAX_QUOTE + 10) + 600)


def test_the_caret_stays_under_the_span_after_escapes_and_cuts():
    shown, caret = _quote("a\x1bb = c;", Location("f", 1, 3, 1, 4))
    assert shown == "a\\x1bb = c;" and caret.index("^") == shown.index("b =")
    text = "x" * 1000 + "span" + "y" * 1000
    shown, caret = _quote(text, Location("f", 1, 1001, 1, 1005))
    assert shown.startswith("...") and shown.endswith("...") and len(shown) == MAX_QUOTE + 6
    assert shown[caret.index("^") : caret.index("^") + 4] == "span" and caret.endswith("^~~~")
    assert _quote("\tab", Location("f", 1, 3, 1, 4)) == ("\tab", "\t ^")
    assert printable("tab\tok") == "tab\tok" and printable("\u00e9t\u00e9") == "\u00e9t\u00e9"
