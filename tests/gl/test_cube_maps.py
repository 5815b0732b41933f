"""Cube map channels on the NumPy backend against llvmpipe (Mesa 22.3), bit for bit: face
selection, face coordinates, seamless filtering across edges and corners, mipmap levels and the
per-pixel implicit LOD (glslcheck/backends/numpy_engine/cube_maps.py; docs/llvmpipe.md, "Cube
maps"). The expected values are the driver's, rendered in the same test."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from glslcheck.backends import registry as api
from glslcheck.backends.driver_profile import host_fma
from glslcheck.shadertoy.bindings import CUBE_FACES

SIZE = (128, 64)

# Eight 32x32 cells, each its own family of directions; q runs over about -1.1 .. 1.1 in a cell,
# so each face is crossed past all four edges and corners (on an 8x8 face the texels within
# half a texel of an edge, |q| > 0.875, fall off it; at 4x4, 2x2 and 1x1 levels nearly all do).
# The direction is a highp local: a helper function's return value would reach the lookup
# rounded to float16 on llvmpipe (Mesa lowers a precision-less return temporary that feeds a
# lowp sampler's coordinate), which is not the cube code's business.
DIRECTIONS = """
    vec2 cell = floor(fragCoord / 32.0);
    vec2 q = (fragCoord - cell * 32.0 - 16.0) * 0.069;
    int k = int(cell.x) + 4 * int(cell.y);
    vec3 d = vec3(q.x, q.x, q.y);  // |x| == |y|: the tie rules of the face choice
    if (k == 0) d = vec3(1.0, q.x, q.y);
    if (k == 1) d = vec3(-1.0, q.y, q.x);
    if (k == 2) d = vec3(q.x, 1.0, q.y);
    if (k == 3) d = vec3(q.y, -1.0, q.x);
    if (k == 4) d = vec3(q.x, q.y, 1.0);
    if (k == 5) d = vec3(q.y, q.x, -1.0);
    if (k == 6) d = vec3(q.x, q.y * q.x, 0.9 - q.y);  // faces meeting inside 2x2 quads
"""


# textureGrad's derivative along y in the lookups below: it grows up the picture
_GY = "vec3(0.0, fragCoord.y / 64.0, 0.01 * fragCoord.x))"


def _faces(folder, n: int, seed: int) -> None:
    """Six faces of random RGBA texels: every face, texel and level distinct."""
    rng = np.random.default_rng(seed)
    folder.mkdir()
    for name in CUBE_FACES:
        texels = rng.integers(0, 256, (n, n, 4), dtype=np.uint8)
        Image.fromarray(texels, "RGBA").save(folder / f"{name}.png")


def _render_both(tmp_path, lookup: str, filt: str, n: int = 8):
    _faces(tmp_path / "sky", n, seed=3)
    (tmp_path / "Image.glsl").write_text(
        "void mainImage(out vec4 fragColor, in vec2 fragCoord) {"
        + DIRECTIONS
        + f"    fragColor = {lookup};\n}}\n"
    )
    channels = {"Image": {"iChannel0": {"cubemap": "sky", "filter": filt}}}
    (tmp_path / "channels.json").write_text(json.dumps(channels))
    ours = api.compile(str(tmp_path), backend="numpy").render(size=SIZE)
    theirs = api.compile(str(tmp_path), backend="gl").render(size=SIZE)
    return ours, theirs


def _assert_same(ours, theirs):
    assert ours[..., :3].std() > 0.05  # the faces' texels, not a constant
    if host_fma():  # llvmpipe fuses its lerps only where the CPU has FMA (docs/llvmpipe.md)
        assert np.array_equal(ours, theirs), (
            f"{int((ours != theirs).any(-1).sum())} of {ours[..., 0].size} pixels differ"
        )
    else:  # a last-bit difference of a lerp can cross one lowp truncation step
        assert np.abs(ours - theirs).max() <= 2.0**-10


@pytest.mark.usefixtures("llvmpipe")
@pytest.mark.parametrize(
    "filt, lookup",
    [
        ("nearest", "texture(iChannel0, d)"),
        ("linear", "texture(iChannel0, d)"),
        ("linear", "texture(iChannel0, d * 1e-3) + texture(iChannel0, -d) * 0.5"),
        ("mipmap", "textureLod(iChannel0, d, fragCoord.y / 20.0)"),  # levels 0..3 and between
        ("mipmap", "texture(iChannel0, d * (1.0 + fragCoord.x))"),  # implicit LOD, per pixel
        ("mipmap", "texture(iChannel0, d, fragCoord.x / 32.0 - 2.0)"),  # with a bias
        # the given derivatives carried onto each pixel's face: levels 0..3 and between
        ("mipmap", "textureGrad(iChannel0, d, vec3(fragCoord.x / 64.0, 0.0, 0.0), " + _GY),
        ("mipmap", "textureGrad(iChannel0, d, dFdx(d) * (1.0 + fragCoord.x / 16.0), dFdy(d) * d)"),
        ("mipmap", "textureGrad(iChannel0, d * (fragCoord.x * 1e3), vec3(fragCoord.y * 30.0), d)"),
        # rho^2 infinite (from huge and from infinite derivatives) or NaN reads level 0
        ("mipmap", "textureGrad(iChannel0, d, vec3(1e30, 0.0, 3e30) * fragCoord.x, d)"),
        ("mipmap", "textureGrad(iChannel0, d, d * (fragCoord.x - 64.0) * 1e30 * 1e30, d)"),
        ("linear", "textureGrad(iChannel0, d, vec3(fragCoord.x / 64.0), d)"),  # no levels
        # constant arguments reach the lowp sampler as float16 (3e29: infinite, level 0)
        ("mipmap", "textureGrad(iChannel0, d, vec3(0.3), vec3(0.0))"),
        ("mipmap", "textureGrad(iChannel0, d * 1e30, vec3(3e29), vec3(0.0))"),
        ("mipmap", "textureLod(iChannel0, d, 1.3) + texture(iChannel0, vec3(0.3, -0.7, 0.55))"),
    ],
)
def test_cube_lookups_bit_for_bit(tmp_path, filt, lookup):
    _assert_same(*_render_both(tmp_path, lookup, filt))


@pytest.mark.usefixtures("llvmpipe")
@pytest.mark.parametrize(
    "lookup",
    ["textureLod(iChannel0, d, fragCoord.y / 24.0)", "textureGrad(iChannel0, d, d * 0.2, " + _GY],
)
def test_cube_lookups_on_a_face_size_that_is_no_power_of_two(tmp_path, lookup):
    # 6x6 faces: levels 6, 3, 1 (the halved size rounded down)
    _assert_same(*_render_both(tmp_path, lookup, "mipmap", 6))


@pytest.mark.usefixtures("llvmpipe")
def test_texture_size_of_a_cube_map(tmp_path):
    # (constant levels: llvmpipe answers a size query with one LOD per SIMD vector, measured)
    lookup = (
        "vec4(vec2(textureSize(iChannel0, 0)), vec2(textureSize(iChannel0, 2)))"
        " + texture(iChannel0, d)"
    )
    ours, theirs = _render_both(tmp_path, lookup, "mipmap")
    assert np.all(ours[..., 0] >= 8.0) and np.all(ours[..., 2] >= 2.0)
    _assert_same(ours, theirs)


@pytest.mark.usefixtures("llvmpipe")
def test_the_skybox_scene_verifies_bit_for_bit(tmp_path):
    # benchmarks/scenes/skybox: a mirror sphere reflecting a mipmapped sky box (implicit LOD on
    # a curved mirror, the sky behind it), frames at several times as the camera turns
    from glslcheck.verification.verify import verify_frames

    scene = Path(__file__).resolve().parents[2] / "benchmarks" / "scenes" / "skybox"
    results = list(verify_frames(str(scene), size=(96, 54), times=[0.0, 1.7, 4.2, 9.9]))
    assert len(results) == 4 and all(r.match for r in results)
    if host_fma():
        assert max(r.comparison.max_abs_error for r in results) == 0.0


@pytest.mark.usefixtures("llvmpipe")
def test_texture_grad_lod_bit_for_bit(gl):
    """textureGrad's LOD itself: a highp cube map whose levels hold their own index returns the
    LOD (k + fraction, every lerp exact), compared with the NumPy backend's lookup on the same
    levels. The directions and derivatives are the driver's own values, read back from it. Each
    of six cells keeps to one face's inner 80% and the LOD below 3 (64x64 faces, levels down to
    8x8): no texel falls off a face, where llvmpipe's per-vector corner weights would round the
    levels' values (docs/llvmpipe.md, "Cube maps"). The derivatives vary per pixel and reach
    every face axis and sign."""
    from glslcheck.backends.gl.program import VERTEX_SHADER, _bind_channel
    from glslcheck.backends.numpy_engine.textures import TextureFunctions
    from glslcheck.shadertoy.channels import ChannelInput

    n, count, (w, h) = 64, 7, (96, 64)
    chan = ChannelInput(np.zeros((6, n, n, 4), np.float32), "mipmap", "clamp", False, cube=True)
    chan._levels = [np.full((6, n >> k, n >> k, 4), float(k), np.float32) for k in range(count)]
    body = """
    vec2 f = gl_FragCoord.xy;
    vec2 cell = floor(f / 32.0);
    vec2 q = (f - cell * 32.0 - 16.0) * 0.05;  // -0.775 .. 0.775
    int k = int(cell.x) + 3 * int(cell.y);
    vec3 d = vec3(1.0, q.x, q.y);
    if (k == 1) d = vec3(q.y, -1.3, q.x * 1.3);
    if (k == 2) d = vec3(q.x * 0.5, q.y * 0.5, 0.5);
    if (k == 3) d = vec3(-2.0, q.x * 2.0, q.y * 2.0);
    if (k == 4) d = vec3(q.x, 1.0, q.y);
    if (k == 5) d = vec3(q.y, q.x, -1.0);
    vec3 gx = vec3(q.x * 0.02, 0.0008 * f.x, q.y * 0.01);
    vec3 gy = vec3(0.0006 * f.y, q.x * q.y * 0.02, 0.001 * (f.x - f.y));
"""
    fs = (
        "#version 300 es\nprecision highp float;\nprecision highp samplerCube;\n"
        "uniform samplerCube t;\nuniform int what;\nout vec4 o;\nvoid main() {"
        + body
        + "    o = what == 0 ? textureGrad(t, d, gx, gy) : vec4(what == 1 ? d : what == 2 ? gx"
        " : gy, 0.0);\n}\n"
    )
    prog = gl.program(vertex_shader=VERTEX_SHADER, fragment_shader=fs)
    tex = _bind_channel(gl, 0, chan)
    out = gl.texture((w, h), 4, dtype="f4")
    fbo = gl.framebuffer([out])
    got = []
    for what in range(4):
        prog["what"] = what
        fbo.use()
        fbo.clear()
        gl.vertex_array(prog, []).render(vertices=3)
        got.append(np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32).reshape(-1, 4))
    for obj in (fbo, out, tex, prog):
        obj.release()

    class Reference(TextureFunctions):
        F = np.float32
        lp = object()

    lod, (d, gx, gy) = got[0][:, 0], (g[:, :3].T for g in got[1:])
    ours = Reference().textureGrad(chan, d, gx, gy)[0]
    assert lod.max() < 3.0 and (lod > 0).mean() > 0.4  # (the rest clamped to level 0)
    assert len(np.unique(np.floor(lod))) == 3
    assert np.array_equal(ours, lod), f"{int((ours != lod).sum())} of {lod.size} pixels differ"


@pytest.mark.usefixtures("llvmpipe")
def test_a_glossy_mirror_read_with_texture_grad_verifies(tmp_path):
    # tests/gl/glossy_mirror: a sphere in a sky box, its reflection read with textureGrad, the
    # derivatives widened up to 25 times on its glossy side (LODs down to the 1x1 level), the sky
    # with its own derivatives given explicitly. A pixel whose 4x2 SIMD vector holds another that
    # reads a face corner takes llvmpipe's corner weights (not emulated, docs/llvmpipe.md): its
    # last bits, then at most one lowp truncation step (2^-10 of a texel of at most 1). Measured:
    # 2 such pixels in these 4 frames, 1 in 10 frames at 800x450; every other pixel is equal.
    from glslcheck.verification.verify import verify_frames

    scene = Path(__file__).resolve().parent / "glossy_mirror"
    results = list(verify_frames(str(scene), size=(200, 112), times=[0.0, 1.7, 4.2, 9.9]))
    assert len(results) == 4 and all(r.match for r in results)
    assert max(r.comparison.max_abs_error for r in results) <= 2.0**-10
    differing = sum(int((r.comparison.error_map > 0).sum()) for r in results)
    assert differing <= 8  # of 89600 pixels: the rare corner vectors, not a LOD rule
