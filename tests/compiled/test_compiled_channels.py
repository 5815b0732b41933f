"""Textures and Buffers in the compiled engine against the NumPy backend, bit for bit.

Every lookup built-in on every filter and wrap (images of power-of-two and other sizes, a Buffer
with feedback), lookups through a sampler parameter and under a divergent branch, arithmetic on
lowp lookups (float16 where the NumPy backend computes it so), texelFetch and textureSize, over
several frames (the Buffer carried from frame to frame by the one multipass driver), per pixel
and in lockstep, at even and odd sizes (helper pixels past the edge of a quad). The NumPy
backend's sampling is llvmpipe's (tests/channels/test_channels.py checks it against GL), so the
compiled engine must give its bits. Cube maps too (nearest, linear and mipmap channels, explicit
and implicit LODs, textureGrad)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from image_bits import assert_same, differing_pixels, frame_text
from PIL import Image

import glslcheck
from glslcheck.base.diagnostics import GlslError

FRAMES = 3

BUFFER_A = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    vec2 flow = 0.01 * vec2(sin(uv.y * 12.0 + iTime), cos(uv.x * 10.0 - iTime));
    vec4 prev = texture(iChannel0, uv + flow);
    vec4 img = textureLod(iChannel1, uv * 3.0 - 1.0, 0.0);
    float s = smoothstep(0.2, 0.0, length(uv - 0.5 - 0.2 * vec2(cos(iTime), sin(iTime))));
    fragColor = prev * 0.9 + img * 0.05 + vec4(s, 0.5 * s, float(iFrame) * 0.1, 1.0);
}
"""

# every lookup that reads no implicit LOD of a mipmap channel: one pixel a call can run it
IMAGE_PLAIN = """vec4 lookup(sampler2D s, vec2 p) { return texture(s, p * 1.7); }
void mainImage(out vec4 c, in vec2 fc) {
    vec2 uv = fc / iResolution.xy;
    vec2 q = (uv - 0.5) * (1.0 + 6.0 * uv.x * uv.x) + vec2(0.1 * iTime, 0.0);
    vec4 a = texture(iChannel1, q) + texture(iChannel2, q * 3.0, 0.5);
    a += textureOffset(iChannel1, q, ivec2(1, -1)) + textureProj(iChannel2, vec3(q, 1.0 + uv.y));
    a += textureProj(iChannel1, vec4(q, 0.0, 0.5 + uv.x));
    a += textureLod(iChannel0, q, uv.x * 7.0 - 1.0) + textureLodOffset(iChannel0, q, 2.3,
        ivec2(-2, 1));
    a += textureGrad(iChannel0, q, vec2(uv.x * 0.3, 0.01), vec2(0.0, uv.y * 0.2));
    a += lookup(iChannel1, q) + lookup(iChannel3, uv);
    if (uv.x > 0.4) {
        a += texture(iChannel2, q * 3.0);
    }
    a += texelFetch(iChannel3, ivec2(fc) - 3, 0) + texelFetchOffset(iChannel1, ivec2(fc), 0,
        ivec2(2, 1));
    a += vec4(vec2(textureSize(iChannel0, 1)), vec2(textureSize(iChannel3, 0))) * 0.01;
    a.x += texture(iChannel2, q).x * 0.1 + 2.1;
    a.yzw -= pow(texture(iChannel1, uv).rgb, vec3(2.0)) * 4.0 - texture(iChannel3, uv).xyz / 3.0;
    c = a + iChannelResolution[0].x * 1e-3;
}
"""

# implicit LODs of a mipmap channel (2x2 quads: lockstep only), with a bias, through a sampler
# parameter, under a divergent branch and beside dFdx
IMAGE_QUADS = """vec4 lookup(sampler2D s, vec2 p) { return texture(s, p * 1.7); }
void mainImage(out vec4 c, in vec2 fc) {
    vec2 uv = fc / iResolution.xy;
    vec2 q = (uv - 0.5) * (1.0 + 30.0 * uv.x * uv.x) + vec2(0.1 * iTime, 0.0);
    vec4 a = texture(iChannel0, q) + texture(iChannel0, q, 1.5) + lookup(iChannel0, q);
    a += textureOffset(iChannel0, q, ivec2(1, -1)) + textureProj(iChannel0, vec3(q, 1.0 + uv.y));
    a += textureGrad(iChannel0, q, dFdx(q) * 3.0, dFdy(q));
    if (uv.y > 0.3 + 0.2 * sin(uv.x * 9.0)) {
        a += texture(iChannel0, q * 5.0) + lookup(iChannel1, q);
    }
    a += texture(iChannel3, uv) + texture(iChannel0, q).x * 0.1 + 2.1;
    c = a;
}
"""


def _png(path, w, h, seed):
    rng = np.random.default_rng(seed)
    Image.fromarray(rng.integers(0, 256, (h, w, 4), dtype=np.uint8), "RGBA").save(path)


def _folder(tmp_path, image: str) -> str:
    _png(tmp_path / "npot.png", 13, 9, 1)
    _png(tmp_path / "pot.png", 16, 8, 2)
    (tmp_path / "Buffer A.glsl").write_text(BUFFER_A)
    (tmp_path / "Image.glsl").write_text(image)
    channels = {
        "Buffer A": {
            "iChannel0": {"buffer": "Buffer A"},
            "iChannel1": {"texture": "npot.png", "filter": "linear", "wrap": "repeat"},
        },
        "Image": {
            "iChannel0": {"texture": "npot.png", "filter": "mipmap", "wrap": "repeat"},
            "iChannel1": {"texture": "pot.png", "filter": "linear", "wrap": "clamp"},
            "iChannel2": {"texture": "pot.png", "filter": "nearest", "wrap": "repeat"},
            "iChannel3": {"buffer": "Buffer A", "filter": "linear"},
        },
    }
    (tmp_path / "channels.json").write_text(json.dumps(channels))
    return str(tmp_path)


def _agree(folder: str, size, output: str = "Image") -> None:
    kw = dict(size=size, time=1.3, frame=FRAMES - 1)
    want = glslcheck.compile(folder, backend="numpy", output=output).render(**kw)
    prog = glslcheck.compile(folder, backend="compiled", output=output)
    got = prog.render(**kw)
    assert np.isfinite(want).all()
    what = f"{output} at {frame_text(**kw)}"
    assert_same(got, want, what=what, names=("compiled", "numpy"), mode="bits_any_nan")


@pytest.mark.parametrize("lanes", ["0", "8"])
@pytest.mark.parametrize("size", [(40, 24), (41, 23)])
def test_lookups_and_buffers_bit_for_bit(numba, tmp_path, monkeypatch, lanes, size):
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", lanes)
    folder = _folder(tmp_path, IMAGE_PLAIN)
    _agree(folder, size)
    _agree(folder, size, output="Buffer A")


@pytest.mark.parametrize("size", [(40, 24), (41, 23)])
def test_implicit_mipmap_lods_bit_for_bit(numba, tmp_path, size):
    """The default program: a pass with implicit mipmap LODs renders in lockstep from its first
    frame (2x2 quads), the others per pixel."""
    folder = _folder(tmp_path, IMAGE_QUADS)
    _agree(folder, size)


def test_lowp_arithmetic_is_float16_and_changes_bits(numba, tmp_path):
    """The float16 tree is what the engines agree on, and it matters: computed in float32 (the
    tree's written form, which exact samplers select), `texture(..).x * 0.1 + 2.1` differs."""
    image = """void mainImage(out vec4 c, in vec2 fc) {
    vec2 uv = fc / iResolution.xy;
    c = vec4(texture(iChannel1, uv).x * 0.1 + 2.1, -texture(iChannel1, uv * 2.0).y / 3.0,
             pow(texture(iChannel1, uv).z, 2.0) * 0.3, 1.0);
}
"""
    folder = _folder(tmp_path, image)
    kw = dict(size=(16, 8), time=0.0)
    low = glslcheck.compile(folder, backend="compiled")
    want = glslcheck.compile(folder, backend="numpy").render(**kw)
    got = low.render(**kw)
    lowp = f"lowp samplers at {frame_text(**kw)}"
    assert_same(got, want, what=lowp, names=("compiled", "numpy"), mode="bits_any_nan")
    exact, exact_numpy = (glslcheck.compile(folder, backend=b) for b in ("compiled", "numpy"))
    exact.impl.lowp_samplers = exact_numpy.impl.lowp_samplers = False  # (WebGL's exact lookups)
    got_exact = exact.render(**kw)
    assert differing_pixels(got_exact, want, "bits_any_nan") > 0
    exact_what = f"exact samplers at {frame_text(**kw)}"
    got_numpy = exact_numpy.render(**kw)
    assert_same(
        got_exact, got_numpy, what=exact_what, names=("compiled", "numpy"), mode="bits_any_nan"
    )


# float16 trees of every shape lower_precision.float16_code writes: a square of a square, a
# constant sunk into a square, negations, vectors and scalars mixed, two samplers in one tree
FLOAT16_TREES = """void mainImage(out vec4 c, in vec2 fc) {
    vec2 uv = fc / iResolution.xy;
    vec3 a = pow(texture(iChannel1, uv).rgb, vec3(2.0)) * 4.0 - texture(iChannel2, uv).xyz / 3.0;
    float b = 0.5 * pow(pow(texture(iChannel2, uv * 3.0).x, 2.0) * 2.0 - 0.25, 2.0)
        - -texture(iChannel1, uv).w;
    vec2 d = (texture(iChannel1, uv).xy - 0.5) * (2.0 + texture(iChannel2, uv.yx).zw) / 7.0;
    c = vec4(a + b, d.x + d.y);
}
"""


@pytest.mark.parametrize("lanes", ["0", "8"])
def test_float16_trees_bit_for_bit(numba, tmp_path, monkeypatch, lanes):
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", lanes)
    folder = _folder(tmp_path, FLOAT16_TREES)
    kw = dict(size=(16, 8), time=0.0)
    want = glslcheck.compile(folder, backend="numpy").render(**kw)
    got = glslcheck.compile(folder, backend="compiled").render(**kw)
    what = f"FLOAT16_TREES at {frame_text(**kw)}"
    assert_same(got, want, what=what, names=("compiled", "numpy"), mode="bits_any_nan")
    # and the lowp forms matter at these pixels: exact samplers (float32 lookups and arithmetic)
    # give other bits
    exact = glslcheck.compile(folder, backend="compiled")
    exact.impl.lowp_samplers = False
    assert differing_pixels(exact.render(**kw), want, "bits_any_nan") > 0


CUBE_PLAIN = """vec4 sky(samplerCube s, vec3 d) { return texture(s, d.zxy); }
void mainImage(out vec4 c, in vec2 fc) {
    vec2 q = (fc / iResolution.xy - 0.5) * 2.6;
    vec3 d = vec3(q, 1.0 - 0.4 * iTime);
    vec4 a = texture(iChannel0, d) + texture(iChannel1, -d.yzx) + sky(iChannel1, d);
    a += textureLod(iChannel2, d.zyx, q.x * 3.0 + 1.0) + textureLod(iChannel2, d, 0.0);
    if (q.y > 0.2 * sin(q.x * 7.0)) {
        a += texture(iChannel0, vec3(d.x, -1.0, d.y));
    }
    a += vec4(vec2(textureSize(iChannel2, 1)), vec2(textureSize(iChannel0, 0))) * 0.01;
    a.x += texture(iChannel1, d).x * 0.1 + 2.1;
    c = a;
}
"""

# implicit cube LODs (per pixel, from fine derivatives: lockstep only), a bias, through a
# sampler parameter and under a divergent branch
CUBE_QUADS = """vec4 sky(samplerCube s, vec3 d) { return texture(s, d); }
void mainImage(out vec4 c, in vec2 fc) {
    vec2 q = (fc / iResolution.xy - 0.5) * (1.0 + 9.0 * fc.x / iResolution.x);
    vec3 d = vec3(q.x, q.y * q.x, 0.9 - q.y);
    vec4 a = texture(iChannel2, d) + texture(iChannel2, d.yzx * 3.0, 1.5) + sky(iChannel2, -d);
    if (q.y > 0.3 * sin(q.x * 9.0)) {
        a += texture(iChannel2, d * 5.0);
    }
    c = a + texture(iChannel0, d);
}
"""


def _cube_folder(tmp_path, image: str) -> str:
    for name, n, seed in (("sky8", 8, 3), ("sky6", 6, 4)):
        (tmp_path / name).mkdir()
        for k, face in enumerate(("px", "nx", "py", "ny", "pz", "nz")):
            _png(tmp_path / name / f"{face}.png", n, n, seed * 10 + k)
    (tmp_path / "Image.glsl").write_text(image)
    channels = {
        "Image": {
            "iChannel0": {"cubemap": "sky6", "filter": "nearest"},
            "iChannel1": {"cubemap": "sky8", "filter": "linear"},
            "iChannel2": {"cubemap": "sky6", "filter": "mipmap"},
        }
    }
    (tmp_path / "channels.json").write_text(json.dumps(channels))
    return str(tmp_path)


@pytest.mark.parametrize("lanes", ["0", "8"])
@pytest.mark.parametrize("size", [(40, 24), (41, 23)])
def test_cube_map_lookups_bit_for_bit(numba, tmp_path, monkeypatch, lanes, size):
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", lanes)
    _agree(_cube_folder(tmp_path, CUBE_PLAIN), size)


@pytest.mark.parametrize("size", [(40, 24), (41, 23)])
def test_implicit_cube_lods_bit_for_bit(numba, tmp_path, size):
    _agree(_cube_folder(tmp_path, CUBE_QUADS), size)


# textureGrad on each kind of cube map channel, with derivatives that vary per pixel, through a
# sampler parameter, infinite ones (rho^2 read as 0) under a divergent branch
CUBE_GRAD = """vec4 sky(samplerCube s, vec3 d, vec3 gx, vec3 gy) {
    return textureGrad(s, d, gx, gy);
}
void mainImage(out vec4 c, in vec2 fc) {
    vec2 q = (fc / iResolution.xy - 0.5) * 2.6;
    vec3 d = vec3(q.x, q.y * q.x, 0.9 - q.y);
    vec3 gx = vec3(fc.x * 0.003, 0.02, q.y * 0.05) * exp2(q.x * 4.0);
    vec3 gy = vec3(0.01, fc.y * 0.02, -0.03);
    vec4 a = textureGrad(iChannel2, d, gx, gy) + sky(iChannel2, d.yzx, gy, gx);
    a += textureGrad(iChannel0, d, gx, gy) + textureGrad(iChannel1, -d, gx, gy);
    if (q.y > 0.2 * sin(q.x * 7.0)) {
        a += textureGrad(iChannel2, d * 3.0, vec3(1.0 / 0.0, 0.0, 0.0) * q.x, gy);
    }
    c = a;
}
"""


@pytest.mark.parametrize("lanes", ["0", "8"])
@pytest.mark.parametrize("size", [(40, 24), (41, 23)])
def test_cube_texture_grad_bit_for_bit(numba, tmp_path, monkeypatch, lanes, size):
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", lanes)
    _agree(_cube_folder(tmp_path, CUBE_GRAD), size)


# constant coordinates, LODs, biases and derivatives, rounded to float16 for the lowp channels
# (nir_fold.lower_precision.float16_lookup_args), through a sampler parameter too
CONSTANT_ARGS = """vec4 look(samplerCube s, vec3 d) { return textureLod(s, d, 1.3); }
const float L = 0.3;
void mainImage(out vec4 c, in vec2 fc) {
    vec2 q = fc / iResolution.xy - 0.5;
    vec3 d = vec3(q, 0.7);
    vec4 a = textureLod(iChannel2, d, 1.3) + look(iChannel2, d.yxz) + textureLod(iChannel2, d, L);
    a += textureGrad(iChannel2, d, vec3(0.3), vec3(0.0)) + texture(iChannel1, vec3(0.3, -0.7, L));
    a += textureGrad(iChannel2, d * 1e30, vec3(3e29), vec3(0.0));
    c = a;
}
"""


@pytest.mark.parametrize("lanes", ["0", "8"])
def test_constant_lookup_arguments_bit_for_bit(numba, tmp_path, monkeypatch, lanes):
    monkeypatch.setenv("GLSLCHECK_COMPILED_LANES", lanes)
    _agree(_cube_folder(tmp_path, CONSTANT_ARGS), (40, 24))


def test_texture_grad_offset_on_a_cube_map_is_a_located_error(numba, tmp_path):
    # GLSL ES 3.00 has no offset form of a cube map lookup: no samplerCube overload matches, so
    # the channel is not sampled as a cube map (semantics/channel_types.py), located at it
    image = (
        "void mainImage(out vec4 c, in vec2 f) {\n"
        "    c = textureGradOffset(iChannel1, vec3(f, 1.0), vec3(1.0), vec3(0.0), ivec2(1));\n}\n"
    )
    folder = _cube_folder(tmp_path, image)
    for backend in ("numpy", "compiled"):
        with pytest.raises(GlslError) as err:
            glslcheck.compile(folder, backend=backend).render(size=(8, 4))
        d = err.value.diagnostics[0]
        assert "not sampled as one" in d.message, (backend, d.message)
        assert (d.loc.line, d.loc.column) == (2, 27), backend


def test_a_mipmap_channel_the_program_was_not_made_for_is_refused(numba, make_shader):
    """Implicit LODs need the quads' differences, generated only for the channels bound with
    mipmaps: a program made without them refuses such an input rather than read level 0."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate
    from glslcheck.shadertoy.channels import ChannelInput

    shader = make_shader(
        "void mainImage(out vec4 c, in vec2 f) { c = texture(iChannel0, f / iResolution.xy); }\n"
    )
    source, path = generate(shader, lanes=0)
    texels = np.ones((4, 4, 4), np.float32)
    prog = CompiledProgram(source, path)
    assert prog.render(size=(4, 2), channels=[ChannelInput(texels, "linear")]).shape == (2, 4, 4)
    with pytest.raises(ValueError, match="mipmaps"):
        prog.render(size=(4, 2), channels=[ChannelInput(texels, "mipmap")])
