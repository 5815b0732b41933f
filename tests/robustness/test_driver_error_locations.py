"""Errors the OpenGL driver reports inside Shadertoy's wrapper still point into the user's tab.

Found by tools/fuzz.py (seed 11, input 3208): Mesa rejects an unnamed parameter in a function
definition, and then reports the wrapper's call of mainImage; that error had no location.
"""

from __future__ import annotations

from glslcheck.cli import main


def test_wrapper_error_points_at_the_users_mainimage(tmp_path, gl, capsys):
    shader = tmp_path / "Image.glsl"
    shader.write_text("// credited\nvoid mainImage(out vec4 fragColor,  in vec2) {}\n")
    assert main(["verify", str(shader), "--size", "8x8"]) == 1
    err = capsys.readouterr().err
    assert "Traceback" not in err
    # Every error line names the file, a line and a column.
    heads = [line for line in err.splitlines() if ": error: " in line]
    assert heads and all(line.startswith(f"{shader}:2:") for line in heads), err
