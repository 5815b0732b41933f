"""iChannel sampler types inferred from their uses (glslcheck/semantics/channel_types.py): real
submissions (tests/real_lint f23, f24) sample a cube map with `texture(iChannelN, vec3)`, which
Shadertoy compiles because its wrapper declares a bound cube map's channel samplerCube."""

from __future__ import annotations

from pathlib import Path

from glslcheck.frontend.parser import parse_shader
from glslcheck.lint import lint_paths
from glslcheck.semantics import check
from glslcheck.shadertoy.sources import load_shader

CUBE = """
// the sky: a cube map on iChannel1, read directly and through a helper
vec4 sky(samplerCube box, vec3 dir) { return texture(box, dir); }
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 dir = normalize(vec3(fragCoord, 1.0));
    fragColor = texture(iChannel1, dir) + sky(iChannel1, dir) + textureLod(iChannel1, dir, 0.0)
        + texture(iChannel0, fragCoord / iResolution.xy);
}
"""


def _model(tmp_path: Path, text: str):
    (tmp_path / "Image.glsl").write_text(text)
    shader = load_shader(tmp_path / "Image.glsl")
    return check(parse_shader(shader, "Image"), "Image", collect=True)


def test_a_channel_sampled_only_as_a_cube_map_is_a_samplercube(tmp_path: Path):
    model = _model(tmp_path, CUBE)
    assert model.errors == []
    uses = {
        n.name: str(model.type_of(n))
        for n in model.ast.walk()
        if type(n).__name__ == "Identifier" and n.name in ("iChannel0", "iChannel1")
    }
    assert uses == {"iChannel0": "sampler2D", "iChannel1": "samplerCube"}


def test_a_use_that_fits_both_leaves_the_cube_uses_deciding(tmp_path: Path):
    # textureSize(iChannel1, 0) compiles on a sampler2D and a samplerCube: only the cube map
    # binding compiles the whole program
    use = "vec4(vec2(textureSize(iChannel1, 0)), 0.0, 0.0)"
    model = _model(tmp_path, CUBE.replace("texture(iChannel0, fragCoord / iResolution.xy)", use))
    assert model.errors == []
    kinds = {
        str(model.type_of(n)) for n in model.ast.walk() if getattr(n, "name", "") == "iChannel1"
    }
    assert kinds == {"samplerCube"}


def test_a_channel_with_a_2d_use_too_stays_2d_and_its_errors_stand(tmp_path: Path):
    use = "texture(iChannel1, fragCoord / iResolution.xy)"  # no binding compiles both
    text = CUBE.replace("+ texture(iChannel0, fragCoord / iResolution.xy)", f"+ {use}")
    model = _model(tmp_path, text)
    assert model.errors, "a vec3 lookup of a sampler2D must stay an error"
    assert all("sampler2D" in d.message for d in model.errors), [d.message for d in model.errors]


def test_a_2d_program_is_checked_once_as_before(tmp_path: Path):
    model = _model(
        tmp_path, "void mainImage(out vec4 c, in vec2 p) { c = texture(iChannel0, p); }\n"
    )
    assert model.errors == []
    (use,) = [
        n for n in model.ast.walk() if type(n).__name__ == "Identifier" and n.name == "iChannel0"
    ]
    assert str(model.type_of(use)) == "sampler2D"


def test_lint_runs_every_rule_on_a_cube_map_shader(tmp_path: Path):
    (tmp_path / "Image.glsl").write_text(CUBE)
    result = lint_paths([tmp_path / "Image.glsl"])
    # no compile error, and no "<rule> could not run" line: every rule ran
    assert [
        f.rule for f in result.findings if f.severity == "error" or "could not run" in f.message
    ] == []
