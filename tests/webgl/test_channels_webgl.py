"""Channels on the WebGL backend (glslcheck/backends/webgl/harness.js `bindChannels`): textures
with their filter, wrap, vflip and mipmaps, Buffer A-D with feedback, against the NumPy backend.

What SwiftShader's WebGL does, measured here: it ignores lowp (a lookup returns the exact float32
filtered value), so the NumPy side is compared with its lowp truncation off
(`MultipassProgram.lowp_samplers = False`); nearest and linear lookups and explicit-LOD mipmap
lookups then agree to float32 rounding. Its projective lookups (textureProj*) divide otherwise
than p.xy / p.z (neither that nor p.xy * (1 / p.z) reproduces them): up to 4.7e-4 apart, below
verification/compare.py's 1/255 steps, so not pinned here. A textureLodOffset whose LOD varies per
pixel reads other texels than llvmpipe and NumPy (which agree) at some pixels (up to 0.5 apart,
measured); with a constant LOD the three agree. Its implicit LOD (texture() on a mipmap,
textureGrad) is computed otherwise than llvmpipe's: those pixels are driver-dependent, which `verify
--against webgl` sets apart.
"""

from __future__ import annotations

import itertools
import sys
from pathlib import Path

import numpy as np
import pytest

from glslcheck.backends import registry as api
from glslcheck.cli.main import main
from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.drivers import verify_against_webgl
from glslcheck.verification.verify import compile_backend

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "channels"))
# a fixture
from test_channels import MIPMAP_UV, SIZE, _folder, _png, _sampling_case, feedback  # noqa: E402,F401

ROOT = Path(__file__).resolve().parents[2]


def _exact_numpy(folder):
    """The NumPy backend with SwiftShader's exact (not lowp-truncated) lookup results."""
    prog = api.compile(folder, backend="numpy")
    prog.impl.lowp_samplers = False
    return prog


def test_feedback_with_a_texture_over_30_frames(webgl, gl, feedback):
    shader = load_shader(feedback)
    programs = [compile_backend(shader, b) for b in ("numpy", "webgl", "gl")]
    results = list(verify_against_webgl(shader, size=SIZE, frames=30, programs=programs))
    assert len(results) == 30 and all(r.match for r in results)
    # NumPy truncates lookups to lowp as llvmpipe does, SwiftShader does not; through 30 frames of
    # feedback the truncations add up to 0.0033 (measured), inside the 1/255 steps of
    # verification/compare.py
    assert max(r.comparison.max_abs_error for r in results) < 2.0 / 255
    # without the truncation only float32 rounding remains (sin, mix): 2.0e-6 measured, about 8
    # ulps of values in [1, 2) (ulp 2^-22) after 30 frames; bounded at 16 such ulps
    programs[0] = compile_backend(shader, "numpy")
    programs[0].impl.lowp_samplers = False
    exact = list(verify_against_webgl(shader, size=SIZE, frames=30, programs=programs))
    assert max(r.comparison.max_abs_error for r in exact) <= 16 * 2.0**-22


def test_feedback_really_feeds_back(webgl, feedback):
    prog = api.compile(feedback, backend="webgl", output="Buffer A")
    frames = [prog.render(size=SIZE, frame=i, time=i / 60) for i in range(3)]
    assert not np.array_equal(frames[1], frames[2])
    # cleared to zero before frame 0, alpha kept: alpha = mix(0, texel.a, 0.1) + 0.01 * iFrame
    assert 0.0 < frames[0][..., 3].max() <= 0.1
    again = api.compile(feedback, backend="webgl", output="Buffer A").render(
        size=SIZE, frame=2, time=2 / 60
    )
    assert np.array_equal(again, frames[2])  # frame 2 alone replays frames 0..2


@pytest.mark.parametrize(
    "filt, wrap, vflip",
    list(itertools.product(["nearest", "linear"], ["clamp", "repeat"], [False, True])),
)
def test_each_filter_and_wrap_against_webgl(webgl, tmp_path, filt, wrap, vflip):
    folder = _sampling_case(tmp_path, filt, wrap, vflip, False)
    ours = _exact_numpy(folder).render(size=SIZE)
    theirs = api.compile(folder, backend="webgl").render(size=SIZE)
    if filt == "nearest":
        assert np.array_equal(ours, theirs)  # the same texel, untouched
    else:
        # float32 weights (textures.py); SwiftShader's order of the lerps gave the same bits here
        # (measured 0.0), bounded at 4 ulps of 1 so another order of the same operations passes
        assert np.abs(ours - theirs).max() <= 4 * 2.0**-23
    assert ours[..., :3].std() > 0.1
    # the lowp truncation NumPy applies for llvmpipe is the whole difference: one step of 2^-10
    lowp = api.compile(folder, backend="numpy").render(size=SIZE)
    assert 0.0 < np.abs(lowp - theirs).max() <= 2.0**-10


@pytest.mark.parametrize("wrap", ["clamp", "repeat"])
def test_mipmap_explicit_lod_against_webgl(webgl, tmp_path, wrap):
    _png(tmp_path / "tex.png", 70, 50, seed=5)
    lookup = "textureLod(iChannel0, uv, fragCoord.x / 9.0 - 0.5)"
    body = (
        f"void mainImage(out vec4 fragColor, in vec2 fragCoord) {{\n    {MIPMAP_UV}\n    "
        f"fragColor = {lookup};\n}}\n"
    )
    folder = _folder(
        tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png", "wrap": wrap}}}
    )
    ours = _exact_numpy(folder).render(size=SIZE)
    theirs = api.compile(folder, backend="webgl").render(size=SIZE)
    # the same levels (glslcheck's pyramid, uploaded) blended by frac(lod): 2.0e-6 measured, a
    # float32 LOD fraction's rounding times a texel difference below 1
    assert np.abs(ours - theirs).max() <= 1e-5
    assert ours[..., :3].std() > 0.01


def test_mipmap_implicit_lod_is_driver_dependent(webgl, gl, tmp_path):
    _png(tmp_path / "tex.png", 70, 50, seed=5)
    body = (
        f"void mainImage(out vec4 fragColor, in vec2 fragCoord) {{\n    {MIPMAP_UV}\n    "
        "fragColor = texture(iChannel0, uv);\n}\n"
    )
    folder = _folder(tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png"}}})
    (result,) = verify_against_webgl(folder, size=SIZE)
    # SwiftShader picks other LODs than llvmpipe (0.016 apart at 85 of 2304 pixels, measured):
    # those pixels are the drivers' own difference, and NumPy matches the closer driver there
    assert result.match
    assert result.driver_pixels > 0 and not result.plain.match


def test_cli_verify_against_webgl_on_the_channels_examples(webgl, gl, capsys):
    code = main(
        [
            "verify",
            str(ROOT / "benchmarks" / "scenes" / "feedback"),
            "--against",
            "webgl",
            "--frames",
            "3",
            "--size",
            "64x36",
        ]
    )
    out = capsys.readouterr().out
    assert code == 0 and "verify: match (3 frames)" in out, out


def test_render_pass_on_webgl(webgl, feedback, tmp_path):
    out = tmp_path / "a.npy"
    assert (
        main(
            [
                "render",
                feedback,
                "--backend",
                "webgl",
                "--pass",
                "Buffer A",
                "--frame",
                "2",
                "--time",
                "0.05",
                "--size",
                "64x36",
                "-o",
                str(out),
            ]
        )
        == 0
    )
    ref = api.compile(feedback, backend="webgl", output="Buffer A").render(
        size=SIZE, frame=2, time=0.05
    )
    assert np.array_equal(np.load(out), ref)


def test_channel_time_is_zero_for_images_and_buffers_on_webgl(webgl, tmp_path):
    from test_channels import channel_time_case  # the case and its source: tests/channels

    img = api.compile(channel_time_case(tmp_path), backend="webgl").render(
        size=(8, 4), time=3.0, frame=2
    )
    assert np.array_equal(img, np.broadcast_to(np.float32([0.0, 0.0, 0.0, 1.0]), img.shape))


def test_a_large_texture_is_uploaded_in_pieces_once_and_sampled_as_on_numpy(webgl, tmp_path):
    # 2048x2048 RGBA32F with its mipmaps is 85 MB of texels and 113 MB as base64: too large for
    # one DevTools message (it ended the page). Uploaded in CHUNK_BYTES pieces, once for all
    # frames, it must sample as the NumPy backend does (lowp off, as SwiftShader ignores it).
    from glslcheck.backends.webgl import program as webgl_program

    _png(tmp_path / "tex.png", w=2048, h=2048, seed=3)
    image = (
        "void mainImage(out vec4 c, in vec2 p) {\n"
        "    c = textureLod(iChannel0, p / iResolution.xy, iTime);\n"
        "}\n"
    )
    folder = _folder(
        tmp_path,
        {"Image": image},
        {"Image": {"iChannel0": {"texture": "tex.png", "filter": "mipmap"}}},
    )
    numpy_prog, webgl_prog = _exact_numpy(folder), api.compile(folder, backend="webgl")
    browser = webgl_prog.impl.programs["Image"].browser
    calls = []
    original = browser.call

    def counting(function, *args):
        calls.append(function)
        return original(function, *args)

    browser.call = counting
    try:
        for lod in (0.0, 1.0, 5.0):
            got = webgl_prog.render(size=(64, 36), time=lod)
            want = numpy_prog.render(size=(64, 36), time=lod)
            # explicit-LOD lookups agree to float32 rounding (module docstring)
            np.testing.assert_allclose(got, want, rtol=0, atol=2e-6)
    finally:
        browser.call = original
    assert calls.count("textureBegin") == 1 and calls.count("render") == 3
    assert calls.count("textureChunk") > 1  # more than one piece: the split was exercised
    assert all(size <= webgl_program.KEPT_TEXTURE_BYTES for size in browser.textures.values())


def test_a_cube_map_scene_against_webgl(webgl, gl):
    # SwiftShader's WebGL samples the TEXTURE_CUBE_MAP the page uploads, seamlessly as WebGL 2
    # always does; it ignores lowp (exact lookups) and picks its own implicit LODs, so the
    # comparison is verify's, with the drivers' own differences set apart
    scene = ROOT / "benchmarks" / "scenes" / "skybox"
    results = list(verify_against_webgl(str(scene), size=SIZE, times=[0.0, 2.5]))
    assert len(results) == 2 and all(r.match for r in results)
