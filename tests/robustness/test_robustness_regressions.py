"""Regression tests for bad input: one case per crash the fuzzer (tools/fuzz.py) or a
hand-made limit case found, each with the minimal input, plus the inputs students really produce
(BOM, CRLF, tabs, non-ASCII, NUL, empty files, comment-only files, binary files).

Every case runs the command in-process through `glslcheck.cli.main.main` and asserts the contract
for bad input: no traceback, an exit code in {0, 1, 2}, every error line naming the user's file
with a line and column inside it, and the file left unchanged.
"""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

from glslcheck.cli.main import main

MAIN = "void mainImage(out vec4 fragColor, in vec2 fragCoord) {"


def run_cli(
    command: str,
    data: bytes | str,
    tmp_path: Path,
    name: str = "shader.glsl",
    extra: tuple[str, ...] = (),
) -> tuple[int, str, str]:
    """Run `glslcheck COMMAND FILE` in-process; assert the bad-input contract; return (rc, out,
    err)."""
    path = tmp_path / name
    raw = data.encode("utf-8") if isinstance(data, str) else data
    path.write_bytes(raw)
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main([command, str(path), *extra])
    out_s, err_s = out.getvalue(), err.getvalue()
    assert "Traceback" not in out_s + err_s, err_s
    assert rc in (0, 1, 2), (rc, err_s)
    assert path.read_bytes() == raw, "the command modified the shader file"
    lines = max(raw.count(b"\n"), raw.count(b"\r")) + 1
    for line in (out_s + err_s).splitlines():
        if ": error:" in line and not line.startswith("glslcheck"):
            if rc == 2 and line.startswith(f"{path}: error:"):
                continue  # a file-level I/O or resource error (exit 2): the file, no position
            m = re.match(rf"{re.escape(str(path))}:(\d+):(\d+): error:", line)
            assert m, f"an error without file:line:col: {line!r}"
            assert 1 <= int(m.group(1)) <= lines, line
    return rc, out_s, err_s


def error_lines(err: str) -> list[str]:
    return [line for line in err.splitlines() if ": error:" in line]


# --- crashes found -------------------------------------------------------------------------


@pytest.mark.parametrize("command", ["parse", "check", "lint"])
def test_500_nested_blocks(tmp_path, command):
    """Crash: the checker's statement walk recursed once per `{` and raised RecursionError at
    about 330 levels (fixed in glslcheck/semantics/__init__.py: the recursion limit is raised while
    checking, as frontend/parser.py does while building). 500 levels is a documented limit."""
    text = "void mainImage(out vec4 c, in vec2 f) { " + "{" * 500 + "}" * 500 + " }\n"
    rc, _, err = run_cli(command, text, tmp_path)
    if command != "lint":
        assert rc == 0, err


def test_nesting_beyond_any_limit_is_an_error_at_1_1(tmp_path):
    """5000 nested `1.0+(...)`: deeper than the recursion budget, so a clear error at 1:1."""
    text = (
        "void mainImage(out vec4 c, in vec2 f) { c = vec4("
        + "1.0+(" * 5000
        + "1.0"
        + ")" * 5000
        + "); }\n"
    )
    rc, _, err = run_cli("check", text, tmp_path)
    assert rc == 1
    assert "nested too deeply" in err and ":1:1: error:" in err


# --- inputs students produce ---------------------------------------------------------------

GOOD = f"{MAIN}\n\tfragColor = vec4(fragCoord.x, 0.0, 0.0, 1.0);\n}}\n"


@pytest.mark.parametrize("command", ["parse", "check"])
@pytest.mark.parametrize(
    "variant",
    [
        pytest.param(b"\xef\xbb\xbf" + GOOD.encode(), id="bom"),
        pytest.param(GOOD.replace("\n", "\r\n").encode(), id="crlf"),
        pytest.param(GOOD.replace("\n", "\r").encode(), id="cr"),
        pytest.param(GOOD.replace("\n", "\r\n", 1).encode(), id="mixed"),
        pytest.param(("// héllo wörld, 日本語 comment\n" + GOOD).encode(), id="non-ascii-comment"),
    ],
)
def test_everyday_variants_are_clean(tmp_path, command, variant):
    rc, _, err = run_cli(command, variant, tmp_path)
    assert rc == 0, err


@pytest.mark.parametrize("command", ["parse", "check", "lint"])
def test_non_ascii_identifier_is_a_clear_error(tmp_path, command):
    text = f"{MAIN}\n    float é = 1.0;\n    fragColor = vec4(é);\n}}\n"
    rc, _, err = run_cli(command, text, tmp_path)
    assert rc == 1
    if command != "lint":
        assert error_lines(err)[0].startswith(f"{tmp_path / 'shader.glsl'}:2:11: error:")


@pytest.mark.parametrize("command", ["parse", "check"])
def test_nul_byte(tmp_path, command):
    rc, _, err = run_cli(command, f"{MAIN}\n    fragColor = vec4(1.0);\0\n}}\n", tmp_path)
    assert rc == 1
    assert ":2:27: error:" in err and "NUL" in err


def test_empty_file(tmp_path):
    """parse: an empty file is a valid (empty) program; check: an Image tab without mainImage
    is an error at 1:1; lint: nothing to deduct from a file with no code."""
    assert run_cli("parse", "", tmp_path)[0] == 0
    rc, _, err = run_cli("check", "", tmp_path)
    assert rc == 1 and ":1:1: error:" in err and "mainImage" in err
    assert run_cli("lint", "", tmp_path)[0] in (0, 1)


def test_comment_only_file(tmp_path):
    text = "// nothing here yet\n/* TODO */\n"
    assert run_cli("parse", text, tmp_path)[0] == 0
    rc, _, err = run_cli("check", text, tmp_path)
    assert rc == 1 and ":1:1: error:" in err


@pytest.mark.parametrize("command", ["parse", "check", "lint"])
def test_binary_file_is_exit_2(tmp_path, command):
    rc, _, err = run_cli(command, b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe", tmp_path)
    assert rc == 2 and "not UTF-8" in err


@pytest.mark.parametrize("command", ["parse", "check", "lint"])
def test_unterminated_comment_and_half_written_function(tmp_path, command):
    text = f"{MAIN}\n    fragColor = vec4(\n/* still typing"
    rc, _, _ = run_cli(command, text, tmp_path)
    assert rc == 1


def test_not_utf8_after_a_lone_cr_names_the_right_line(tmp_path):
    """Found by tools/fuzz.py: the not-UTF-8 message counted a lone CR (old Mac line end) as no
    line break, though every other message does, so it named line 1 for a byte on line 3."""
    rc, _, err = run_cli("parse", b"a\rb\rc\xb1\n", tmp_path)
    assert rc == 2 and ":3:2: error: the file is not UTF-8" in err


@pytest.mark.parametrize("command", ["render", "verify"])
def test_huge_size_is_a_usage_error(tmp_path, command):
    """--size 16384x16384 allocated a 4 GiB image and died with a MemoryError traceback
    (now a usage error: at most 4096*4096 pixels)."""
    extra = ("--size", "16384x16384") + (
        ("-o", str(tmp_path / "o.npy")) if command == "render" else ()
    )
    rc, _, err = run_cli(command, f"{MAIN} fragColor = vec4(1.0); }}\n", tmp_path, extra=extra)
    assert rc == 2 and "16,777,216 pixels" in err


@pytest.mark.parametrize("error, code", [(RecursionError, 1), (MemoryError, 2)])
def test_safety_net_turns_recursion_and_memory_errors_into_messages(
    tmp_path, monkeypatch, error, code
):
    """The last resort in cli.main: a stage that still runs out of stack or memory
    prints one line naming the shader instead of a traceback."""
    import glslcheck.semantics as check_module

    def boom(*args, **kwargs):
        raise error()

    monkeypatch.setattr(check_module, "check", boom)
    rc, _, err = run_cli("check", GOOD, tmp_path)
    assert rc == code
    assert err.startswith(str(tmp_path / "shader.glsl"))


@pytest.mark.parametrize("command", ["parse", "check", "lint", "transpile"])
def test_lint_and_other_commands_never_modify_the_file(tmp_path, command):
    """The pre-commit hook and lint never modify a file (run_cli compares the bytes),
    also for a file with findings in every rule family."""
    text = (
        "\xef\xbb\xbfvoid mainImage(out vec4 c, in vec2 p)\r\n{\tfloat x = pow(p.x, "
        "2.0);  \r\n c = vec4(x); }"
    )
    extra = ("-o", str(tmp_path / "out.py")) if command == "transpile" else ()
    run_cli(command, text.encode("latin-1"), tmp_path, extra=extra)


@pytest.mark.parametrize(
    "text",
    [
        "void mainImage(out vec4 , in vec2 fragCoord) {}\n",
        "float f(float) { return 0.5; }\nvoid g(out float, inout vec2 q) { q += 1.0; }\n"
        f"{MAIN}\n    vec2 q = fragCoord; float z; g(z, q);\n    fragColor = vec4(f(2.0), "
        "q * 0.01, 1.0);\n}\n",
    ],
)
def test_unnamed_parameters_render(tmp_path, text):
    """Found by tools/fuzz.py (seed 9, inputs 18849 and 66533, mutants of the lint fixtures):
    the transpiler dropped unnamed parameters, so `shade` unpacked None (TypeError traceback).
    glslangValidator accepts unnamed parameters in a definition (the transpiler now passes them),
    but Mesa rejects them ("formal parameter lacks a name"), so `check` does as the driver:
    a located error, exit 1, and no traceback from any command."""
    rc, _, err = run_cli("check", text, tmp_path)
    assert rc == 1 and "a parameter of a function definition needs a name" in err
    rc, _, err = run_cli(
        "render", text, tmp_path, extra=("--size", "4x2", "-o", str(tmp_path / "o.npy"))
    )
    assert rc == 1 and "Traceback" not in err, err
