"""verify: NumPy against OpenGL on the corpus and every lab part, and proof that it can fail.

Small sizes (160x90) and three times keep CI time low. These need an OpenGL context (the `gl`
fixture): on CI a missing context FAILS the run rather than skipping it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.verify import compile_backend, frame_specs, verify, verify_frames

ROOT = Path(__file__).resolve().parents[2]
SIZE = (160, 90)
TIMES = [0.0, 1.7, 5.3]
CORPUS = sorted(
    p.name for p in (ROOT / "tests" / "corpus").iterdir() if p.suffix in (".glsl", ".frag")
)
LAB_PARTS = sorted(p.name for p in (ROOT / "lab_shaders").iterdir() if (p / "Image.glsl").is_file())


# Every corpus file renders on both backends (tests/corpus/macros.glsl once had an #extension
# after code, which the driver refuses inside the Shadertoy wrapper; glslcheck now reports that
# itself as a preprocessor error, tested in tests/preprocess).
NOT_RENDERABLE: dict[str, str] = {}


@pytest.mark.parametrize("name", [n for n in CORPUS if n not in NOT_RENDERABLE])
def test_corpus_verifies(gl, name):
    # qualifiers.frag is a plain GLSL ES shader (own #version and main) that declares every
    # sampler type but samples none, so both backends render it like any other.
    for time, c in zip(TIMES, verify(ROOT / "tests" / "corpus" / name, size=SIZE, times=TIMES)):
        assert c.match, f"{name} at iTime {time}: {c.summary()}"


@pytest.mark.parametrize("part", LAB_PARTS)
def test_lab_part_verifies(gl, part):
    for time, c in zip(TIMES, verify(ROOT / "lab_shaders" / part, size=SIZE, times=TIMES)):
        assert c.match, f"{part} at iTime {time}: {c.summary()}"


class _Tampered:
    """The NumPy program with +0.1 added to a 20x20 block: a local bug verify must catch."""

    def __init__(self, program):
        self.program = program

    def render(self, **kwargs):
        img = self.program.render(**kwargs).copy()
        img[30:50, 60:80, :3] += 0.1
        return img


def test_a_deliberate_difference_is_caught(gl):
    shader = load_shader(ROOT / "lab_shaders" / "07_final")
    numpy_prog, gl_prog = compile_backend(shader, "numpy"), compile_backend(shader, "gl")
    honest = verify(shader, size=SIZE, time=1.0, programs=[numpy_prog, gl_prog])[0]
    assert honest.match
    c = verify(shader, size=SIZE, time=1.0, programs=[_Tampered(numpy_prog), gl_prog])[0]
    assert not c.match
    assert c.mismatched_pixels >= 300  # the 400-pixel block, less pixels already white (clamped)
    x0, y0, x1, y1 = c.bbox
    assert 60 <= x0 and x1 <= 80 and 30 <= y0 and y1 <= 50
    w = c.worst[0]
    assert w.frag_coord == (w.x + 0.5, SIZE[1] - w.y - 0.5)


def test_a_numpy_only_nan_is_caught(gl, make_shader):
    # Same program on both sides except for one pixel made NaN on the NumPy side.
    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 p) { c = vec4(p / iResolution.xy, 0.5, 1.0); }"
    )
    gl_prog = compile_backend(shader, "gl")

    class OneNaN:
        def render(self, **kwargs):
            kwargs.pop("precision", None)  # a **kwargs render is offered precision; GL has none
            img = gl_prog.render(**kwargs).copy()
            img[5, 7, 1] = np.nan
            return img

    c = verify(shader, size=(32, 16), programs=[OneNaN(), gl_prog])[0]
    assert not c.match and c.nan_numpy == 1 and c.nan_gl == 0
    assert (c.worst[0].x, c.worst[0].y, c.worst[0].kind) == (7, 5, "nan")


def test_same_uniforms_on_both_sides(gl, make_shader):
    body = (
        "c = vec4(fract(iTime * 0.37), float(iFrame) / 100.0, iMouse.x / 64.0 + iTimeDelta,"
        " iFrameRate / 100.0);"
    )
    shader = make_shader("void mainImage(out vec4 c, in vec2 p) { " + body + " }")
    results = list(
        verify_frames(
            shader,
            size=(8, 4),
            frames=3,
            fps=30.0,
            frame=5,
            mouse=(16.0, 8.0, 0.0, 0.0),
            keep_images=True,
        )
    )
    assert [r.spec.frame for r in results] == [5, 6, 7]
    for r in results:
        assert r.match
        assert r.gl_image[0, 0, 1] == pytest.approx(r.spec.frame / 100.0)
        assert r.gl_image[0, 0, 2] == pytest.approx(0.25 + 1 / 30)
        np.testing.assert_allclose(r.numpy_image[..., :3], r.gl_image[..., :3], atol=1e-6)


def test_frame_schedule():
    assert frame_specs() == frame_specs(time=0.0)
    specs = frame_specs(frames=3, fps=30.0, frame=2)
    assert [(s.frame, s.time) for s in specs] == [(2, 2 / 30), (3, 3 / 30), (4, 4 / 30)]
    assert all(s.time_delta == 1 / 30 and s.frame_rate == 30.0 for s in specs)
    assert [s.time for s in frame_specs(times=[0, 0.5])] == [0.0, 0.5]
    with pytest.raises(ValueError):
        frame_specs(time=1.0, frames=2)


def test_supersampling_and_precision_reach_the_numpy_side(gl):
    part = ROOT / "lab_shaders" / "02_point_light"
    assert verify(part, size=(64, 36), samples=4)[0].match
    # mediump emulation differs from the float32 GPU; float64 is closer than float16.
    c16 = verify(part, size=(64, 36), precision="float16")[0]
    c64 = verify(part, size=(64, 36), precision="float64")[0]
    assert c16.max_abs_error >= c64.max_abs_error


# uint(x) of a negative or huge x: the CPU decides what llvmpipe returns
# (backends/driver_profile.py).
UINT_HASH = """
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // negative, in-range and past 2**32 values across the image, through a uint hash
    float x = (fragCoord.x - 80.0) * 1.0e8 + fragCoord.y;
    uint h = uint(x) * 2654435761u;
    fragColor = vec4(float(h >> 24) / 255.0, float((h >> 16) & 255u) / 255.0, 0.0, 1.0);
}
"""


def test_verify_emulates_the_drivers_float_to_uint(gl, tmp_path):
    """verify measures the driver's model and the NumPy side follows it; forced to any other
    model, the same frame mismatches (so the emulation is what makes it match)."""
    from glslcheck.backends.driver_profile import FLOAT_TO_UINT, driver_model
    from glslcheck.verification.verify import compile_backend

    path = tmp_path / "uint_hash.glsl"
    path.write_text(UINT_HASH)
    shader = load_shader(path)
    live = driver_model(gl)
    other = next(m for m in FLOAT_TO_UINT if m != live)
    numpy_side = compile_backend(shader, "numpy")
    getattr(numpy_side, "impl", numpy_side).emulate_float_to_uint(other)
    # verify's own programs, the NumPy side first set to a model that is not the driver's
    [comparison] = verify(
        path, size=(160, 90), programs=[numpy_side, compile_backend(shader, "gl")]
    )
    assert comparison.match, comparison.summary()
    gl_side = compile_backend(shader, "gl")
    for model in FLOAT_TO_UINT:
        if model == live:
            continue
        numpy_side = compile_backend(shader, "numpy")
        getattr(numpy_side, "impl", numpy_side).emulate_float_to_uint(model)
        a = numpy_side.render(size=(160, 90))
        b = gl_side.render(size=(160, 90))
        assert not np.array_equal(a, b), model


def test_a_shader_with_buffers_is_verified_on_the_numpy_backend(gl, make_shader):
    """The default CPU program runs a shader's passes on the NumPy backend (Buffer A-D are not
    the compiled engine's): each frame says so, as verify's text and JSON name it."""
    from glslcheck.verification.verify import verify_frames

    text = "void mainImage(out vec4 c, in vec2 f) { c = vec4(f / iResolution.xy, 0.5, 1.0); }"
    (result,) = verify_frames(make_shader(text, Buffer_A=text), size=(16, 8))
    assert result.match and result.engine == "numpy" and result.to_json()["engine"] == "numpy"
