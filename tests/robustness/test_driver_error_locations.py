"""Errors the OpenGL driver reports inside Shadertoy's wrapper still point into the user's tab.

Found by tools/fuzz.py (seed 11, input 3208): Mesa rejects an unnamed parameter in a function
definition, and then reports the wrapper's call of mainImage; that error had no location.
"""

from __future__ import annotations

from glslcheck.cli.main import main


def test_wrapper_error_points_at_the_users_mainimage(tmp_path, gl, capsys):
    shader = tmp_path / "Image.glsl"
    shader.write_text("// credited\nvoid mainImage(out vec4 fragColor,  in vec2) {}\n")
    assert main(["verify", str(shader), "--size", "8x8"]) == 1
    err = capsys.readouterr().err
    assert "Traceback" not in err
    # Every error line names the file, a line and a column.
    heads = [line for line in err.splitlines() if ": error: " in line]
    assert heads and all(line.startswith(f"{shader}:2:") for line in heads), err


def _driver_errors(tmp_path, text: str, capsys) -> list[str]:
    shader = tmp_path / "Image.glsl"
    shader.write_text(text)
    assert main(["verify", str(shader), "--size", "4x4", "--backends", "gl,gl"]) == 1
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return [line for line in err.splitlines() if ": error: " in line]


def test_a_mesa_preprocessor_error_points_at_its_own_line(tmp_path, gl, capsys):
    # Mesa says "0:25(1): preprocessor error: ..."; it was placed at mainImage's line.
    text = (
        "// a\n#if 1\n#error boom here\n#endif\nvoid mainImage(out vec4 c, "
        "in vec2 p) { c = vec4(1.0); }\n"
    )
    heads = _driver_errors(tmp_path, text, capsys)
    assert heads == [f"{tmp_path / 'Image.glsl'}:3:1: error: #error boom here"]


def test_a_users_line_directive_is_mapped_back_to_the_real_line(tmp_path, gl, capsys):
    # Mesa numbers the lines after `#line 100` from 100; the message points at line 5 of the file.
    text = (
        "// a\n#line 100\nvoid mainImage(out vec4 c, in vec2 p) {\n  c = vec4(1.0);\n  c = "
        "nothing;\n}\n"
    )
    heads = _driver_errors(tmp_path, text, capsys)
    assert heads == [f"{tmp_path / 'Image.glsl'}:5:7: error: `nothing' undeclared"]


def test_a_line_directive_with_a_source_number_in_hex(tmp_path, gl, capsys):
    text = "// a\n#line 0x10 3\nvoid mainImage(out vec4 c, in vec2 p) {\n  c = nothing;\n}\n"
    heads = _driver_errors(tmp_path, text, capsys)
    assert heads == [f"{tmp_path / 'Image.glsl'}:4:7: error: `nothing' undeclared"]


def test_driver_line_map():
    from glslcheck.backends.driver_log import driver_line_map

    text = "a\n#line 10\nb\nc\n#line 0x20 2\nd\n#line 010\ne\n#line FOO\nf\n"
    m = driver_line_map(text)
    assert m[(0, 1)] == [1] and m[(0, 2)] == [2] and m[(0, 10)] == [3] and m[(0, 11)] == [4]
    assert m[(2, 32)] == [6] and m[(2, 8)] == [8]  # octal 010 = 8, the source number stays 2
    assert m[(None, 32)] == [6]  # Mesa prints source 0 whatever `#line` says
    assert max(max(v) for v in m.values()) == 9  # after `#line FOO` the numbering is unknown
