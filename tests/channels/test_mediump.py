"""verify's note on mediump/lowp float arithmetic (glslcheck/semantics/mediump.py): found where the
shader asks for it, and said beside the comparison; llvmpipe's float16 itself is measured by
tools/measure_mediump.py (what it lowers depends on Mesa's passes, so no test pins it)."""

from __future__ import annotations

from glslcheck.semantics.mediump import mediump_declarations
from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.verify import verify_frames

MEDIUMP = """precision mediump float;
// lowp float not_this = 1.0;
/* mediump vec3 nor_this;
*/
vec3 shade(lowp vec3 c, in mediump float k) { return c * k; }
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    highp float h = 1.0;
    mediump mat2 m = mat2(1.0);
    fragColor = vec4(shade(vec3(fragCoord.x / iResolution.x), 0.5), 1.0);
}
"""


def _shader(tmp_path, text):
    path = tmp_path / "s.glsl"
    path.write_text(text)
    return load_shader(str(path)), str(path)


def test_mediump_declarations_with_their_lines(tmp_path):
    shader, path = _shader(tmp_path, MEDIUMP)
    assert mediump_declarations(shader) == [
        (path, 1, "precision mediump float"),
        (path, 5, "lowp vec3"),
        (path, 5, "mediump float"),
        (path, 8, "mediump mat2"),
    ]
    plain, _ = _shader(tmp_path, MEDIUMP.replace("mediump", "highp").replace("lowp", "highp"))
    assert mediump_declarations(plain) == []


def test_verify_notes_a_mediump_shader_and_not_a_highp_one(gl, tmp_path):
    shader, path = _shader(tmp_path, MEDIUMP)
    (result,) = verify_frames(shader, size=(16, 8))
    assert any(
        n.startswith(f"{path}:1: `precision mediump float` (and 3 more): llvmpipe computes")
        and "float16" in n
        for n in result.notes
    ), result.notes
    plain, _ = _shader(tmp_path, MEDIUMP.replace("mediump", "highp").replace("lowp", "highp"))
    (result,) = verify_frames(plain, size=(16, 8))
    assert not any("float16" in n for n in result.notes)
