"""Invalid programs: one small file per rule in tests/check/invalid/<rule>-<n>.glsl.

Each file starts with `// expect: <part of our message>`; the line marked `// ERROR` (line 1 when
none is marked: errors about the file as a whole) is where glslcheck must report it. A second
line `// tab: Common` makes the file a Common tab, compiled alone as Shadertoy does. Every
fixture must also be rejected by glslangValidator on the program Shadertoy builds, so each
rule is checked against the reference compiler, not only against our own reading of the spec.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from glslcheck.base.diagnostics import register_source
from glslcheck.semantics.agreement import glslang_errors, our_errors
from glslcheck.shadertoy.sources import Shader, Source

HERE = Path(__file__).parent / "invalid"
FIXTURES = sorted(HERE.glob("*.glsl"))


def load(path: Path) -> tuple[Shader, str, int]:
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    assert lines[0].startswith("// expect: "), f"{path.name}: first line must be '// expect: ...'"
    expect = lines[0][len("// expect: ") :].strip()
    tab = "Common" if len(lines) > 1 and lines[1].strip() == "// tab: Common" else "Image"
    marked = [i + 1 for i, line in enumerate(lines) if line.rstrip().endswith("// ERROR")]
    line = marked[0] if marked else 1
    shader = Shader(root=str(path))
    register_source(str(path), text)
    shader.tabs[tab] = Source(str(path), text, tab)
    return shader, expect, line


def test_enough_fixtures():
    assert len(FIXTURES) >= 60
    rules = {p.stem.rsplit("-", 1)[0] for p in FIXTURES}
    assert len(rules) >= 30


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_we_reject_with_message_at_line(path):
    shader, expect, line = load(path)
    errors = our_errors(shader)
    assert errors, f"{path.name}: glslcheck accepted it"
    hits = [d for d in errors if expect in d.message]
    assert hits, f"{path.name}: no error says {expect!r}; got {[d.message for d in errors]}"
    assert any(
        d.loc is not None and d.loc.path == str(path) and d.loc.line == line for d in hits
    ), f"{path.name}: expected at line {line}, got {[str(d.loc) for d in hits]}"
    assert all(d.help is None or d.help.strip() for d in errors)


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_glslang_rejects_too(path, glslang):
    shader, _expect, _line = load(path)
    assert glslang_errors(shader), f"{path.name}: glslangValidator accepts this program"
