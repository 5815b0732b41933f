"""Channels and passes (glslcheck/shadertoy/channels.py): channels.json, images, Buffer A-D with
feedback, on both backends, against the GL driver; and the errors of bad channels.json files."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from glslcheck.backends import registry as api
from glslcheck.backends.driver_profile import host_fma
from glslcheck.verification.verify import verify_frames

SIZE = (64, 36)


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
@pytest.mark.parametrize(
    "lookup",
    [
        "textureLod(iChannel0, uv, 1.3) + textureLod(iChannel0, uv, 2.0 * 0.65)",
        "texture(iChannel0, uv, 0.7) + texture(iChannel0, vec2(0.3, 0.7))",
        "textureGrad(iChannel0, uv, vec2(0.03, 0.0), vec2(0.0, fragCoord.y * 1e-4))",
        "textureProj(iChannel0, vec3(0.3, 0.7, 1.3)) + textureLod(iChannel0, uv, L)",
    ],
)
def test_constant_lookup_arguments_reach_the_sampler_as_float16(gl, tmp_path, lookup):
    # A constant coordinate, LOD, bias or derivative (a literal, a constant expression, a const
    # global) reaches the lowp iChannel rounded to float16 on llvmpipe: LOD 1.3 reads
    # 1.2998047 (nir_fold.lower_precision.float16_lookup_args). Without the rounding 812 of the
    # 8192 pixels of `textureLod(iChannel0, uv, 1.3)` at 128x64 differ by a lowp step.
    _png(tmp_path / "tex.png", 64, 64, seed=5)
    body = f"""const float L = 2.3;
void mainImage(out vec4 fragColor, in vec2 fragCoord) {{
    vec2 uv = fragCoord / 64.0;
    fragColor = {lookup};
}}
"""
    folder = _folder(tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png"}}})
    ours = api.compile(folder, backend="numpy").render(size=SIZE)
    theirs = api.compile(folder, backend="gl").render(size=SIZE)
    assert ours[..., :3].std() > 0.01
    if host_fma():  # llvmpipe fuses its lerps only where the CPU has FMA (driver_profile)
        assert np.array_equal(ours, theirs), f"{int((ours != theirs).any(-1).sum())} pixels differ"
    else:
        assert np.abs(ours - theirs).max() <= 2.0**-10


FEEDBACK = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    vec4 prev = texture(iChannel0, uv);
    vec4 img = texture(iChannel1, uv * 2.0 + vec2(0.1 * iTime, 0.0));
    fragColor = mix(prev, img, 0.1) + vec4(0.01 * sin(iTime), 0.0, 0.0, float(iFrame) * 0.01);
}
"""
IMAGE = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    ivec2 t = ivec2(fragCoord) % textureSize(iChannel1, 0);
    fragColor = texture(iChannel0, uv) + 0.25 * texelFetch(iChannel1, t, 0) + \
        iChannelResolution[1].x * 1e-3;
}
"""


def _png(path, w=13, h=9, seed=0):
    rng = np.random.default_rng(seed)
    Image.fromarray(rng.integers(0, 256, (h, w, 4), dtype=np.uint8), "RGBA").save(path)


def _folder(tmp_path, tabs: dict, channels) -> str:
    for name, text in tabs.items():
        (tmp_path / f"{name}.glsl").write_text(text)
    if channels is not None:
        (tmp_path / "channels.json").write_text(
            channels if isinstance(channels, str) else json.dumps(channels)
        )
    return str(tmp_path)


@pytest.fixture
def feedback(tmp_path):
    _png(tmp_path / "tex.png")
    return _folder(
        tmp_path,
        {"Buffer A": FEEDBACK, "Image": IMAGE},
        {
            "Buffer A": {
                "iChannel0": {"buffer": "Buffer A"},
                "iChannel1": {"texture": "tex.png", "filter": "linear"},
            },
            "Image": {
                "iChannel0": {"buffer": "Buffer A", "filter": "nearest"},
                "iChannel1": {"texture": "tex.png", "filter": "nearest"},
            },
        },
    )


def test_feedback_with_a_texture_verifies_over_30_frames(gl, feedback):
    results = list(verify_frames(feedback, size=SIZE, frames=30))
    assert len(results) == 30 and all(r.match for r in results)
    # the linear lookups differ from llvmpipe's in the last float32 bits, which the 10-bit
    # (lowp) truncation of each result can turn into one unit of 2^-11 relative: bounded so
    assert max(r.comparison.max_abs_error for r in results) < 2.0**-11


def test_buffers_carry_state_and_render_frame_n_replays(gl, feedback):
    prog = api.compile(feedback, backend="gl", output="Buffer A")
    frames = [prog.render(size=SIZE, frame=i, time=i / 60) for i in range(4)]
    fresh = api.compile(feedback, backend="gl", output="Buffer A").render(
        size=SIZE, frame=3, time=3 / 60
    )
    assert np.array_equal(frames[3], fresh)  # frame 3 alone runs frames 0..3
    assert not np.array_equal(frames[2], frames[3])
    # cleared to zero before frame 0 and alpha kept (not forced to 1): alpha = mix(0, texel.a, 0.1)
    assert 0.0 < frames[0][..., 3].max() <= 0.1


def _sampling_case(tmp_path, filt, wrap, vflip, highp):
    _png(tmp_path / "tex.png", 7, 5, seed=3)
    head = "precision highp sampler2D;\n" if highp else ""
    body = (
        head
        + """void mainImage(out vec4 c, in vec2 p) {
    vec2 uv = (p + 0.123) / iResolution.xy * 2.6 - 0.8;
    c = texture(iChannel0, uv);
}
"""
    )
    return _folder(
        tmp_path,
        {"Image": body},
        {
            "Image": {
                "iChannel0": {"texture": "tex.png", "filter": filt, "wrap": wrap, "vflip": vflip}
            }
        },
    )


@pytest.mark.parametrize("highp", [False, True])
@pytest.mark.parametrize("vflip", [False, True])
@pytest.mark.parametrize("wrap", ["clamp", "repeat"])
@pytest.mark.parametrize("filt", ["nearest", "linear"])
def test_each_filter_and_wrap_against_gl(gl, tmp_path, filt, wrap, vflip, highp):
    folder = _sampling_case(tmp_path, filt, wrap, vflip, highp)
    ours = api.compile(folder, backend="numpy").render(size=SIZE)
    theirs = api.compile(folder, backend="gl").render(size=SIZE)
    if filt == "nearest":
        assert np.array_equal(ours, theirs)  # bit for bit (the same 10-bit lowp truncation)
    else:
        # float32 weights ordered differently by llvmpipe's code: a few ulps (textures.py); with
        # lowp each result is truncated to 10 mantissa bits, so a last-bit difference can cross one
        # truncation step of 2^-10 relative (texels are at most 1)
        tol = 2.0**-10  # iChannel0 is lowp even with `precision highp sampler2D;` (see textures.py)
        assert np.abs(ours - theirs).max() <= tol
    assert ours[..., :3].std() > 0.1  # the texture really was sampled


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
def test_lowp_sampler_truncates_like_llvmpipe(gl, tmp_path):
    (tmp_path / "tex.png").unlink(missing_ok=True)
    _png(tmp_path / "tex.png", 7, 5, seed=3)
    # the lookup's result stored in a highp variable first: an expression of lowp operands only
    # (texelFetch(...) * 3.14) is itself lowp and llvmpipe truncates its result too (not emulated)
    body = (
        "void mainImage(out vec4 c, in vec2 p) { vec4 t = texelFetch(iChannel0, ivec2(p) % 5, "
        "0); c = t * 3.14159265; }\n"
    )
    folder = _folder(
        tmp_path,
        {"Image": body},
        {"Image": {"iChannel0": {"texture": "tex.png", "filter": "nearest"}}},
    )
    ours = api.compile(folder, backend="numpy").render(size=SIZE)
    theirs = api.compile(folder, backend="gl").render(size=SIZE)
    assert np.array_equal(ours, theirs)


def _cli(*args):
    return subprocess.run(
        [sys.executable, "-m", "glslcheck", *args], capture_output=True, text=True, timeout=120
    )


BAD = [
    (
        {"Image": {"iChannel0": {"texture": "missing.png"}}},
        2,
        '"Image"."iChannel0"."texture": no such file',
    ),
    ({"Image": {"iChannel0": {"texture": "bad.png"}}}, 2, "cannot read the image"),
    ({"Buffer Z": {"iChannel0": {"buffer": "Buffer A"}}}, 2, '"Buffer Z": unknown tab'),
    ({"Image": {"iChannel0": {"buffer": "Buffer B"}}}, 2, "the shader has no Buffer B tab"),
    ({"Image": {"iChannel0": {"buffer": "Image"}}}, 2, "cannot be an input"),
    ({"Image": {"iChannel7": {"buffer": "Buffer A"}}}, 2, '"Image"."iChannel7": unknown key'),
    (
        {"Image": {"iChannel0": {"buffer": "Buffer A", "filter": "cubic"}}},
        2,
        '"filter": must be one of',
    ),
    (
        {"Image": {"iChannel0": {"keyboard": True}}},
        2,
        "keyboard inputs are not supported yet (tab Image, iChannel0)",
    ),
    ('{"Image": ', 2, "channels.json:1:11: error: not valid JSON"),
    (
        {"Image": {"iChannel1": {"buffer": "Buffer A"}}},
        1,
        "Image.glsl:2:29: error: iChannel0 is read but not bound",
    ),
]


@pytest.mark.parametrize("channels, code, message", BAD)
@pytest.mark.parametrize("command", ["render", "verify"])
def test_bad_channels_json(tmp_path, channels, code, message, command):
    (tmp_path / "bad.png").write_bytes(b"not a png")
    image = (
        "void mainImage(out vec4 c, in vec2 p) {\n    c = vec4(1.0) * texture(iChannel0, p);\n}\n"
    )
    folder = _folder(
        tmp_path,
        {"Buffer A": "void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n", "Image": image},
        channels,
    )
    args = ["-o", str(tmp_path / "out.png")] if command == "render" else ["--size", "8x8"]
    r = _cli(command, folder, *args)
    assert r.returncode == code, r.stderr
    assert message in r.stderr and "Traceback" not in r.stderr
    assert not (tmp_path / "out.png").exists()


MIPMAP_UV = """float s = exp2(fragCoord.x / 10.0 - 1.0) * (1.0 + 0.3 * fragCoord.y / 32.0);
    vec2 uv = vec2(fragCoord.x * s, fragCoord.y * s * 0.7 + fragCoord.x * 0.2 * s) / 64.0;"""


@pytest.mark.parametrize("wrap", ["clamp", "repeat"])
@pytest.mark.parametrize(
    "lookup",
    [
        # the implicit LOD of each 2x2 quad, from 0 to past the last level
        "texture(iChannel0, uv)",
        "texture(iChannel0, uv, 0.7)",  # with a bias
        "textureLod(iChannel0, uv, fragCoord.x / 9.0 - 0.5)",
        "textureGrad(iChannel0, uv, vec2(fragCoord.x / 900.0, 0.0), vec2(0.0, "
        "fragCoord.y / 300.0))",
        "textureProjOffset(iChannel0, vec3(uv, 1.5), ivec2(1, 0))",
        "textureProjLod(iChannel0, vec3(uv, 1.5), fragCoord.y / 6.0)",
    ],
)
def test_mipmap_against_gl(gl, tmp_path, lookup, wrap):
    _png(
        tmp_path / "tex.png", 70, 50, seed=5
    )  # odd level sizes on the way down: 70x50, 35x25, 17x12, ...
    body = (
        f"void mainImage(out vec4 fragColor, in vec2 fragCoord) {{\n    {MIPMAP_UV}\n    "
        f"fragColor = {lookup};\n}}\n"
    )
    folder = _folder(
        tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png", "wrap": wrap}}}
    )  # textures default to mipmap
    ours = api.compile(folder, backend="numpy").render(size=SIZE)
    theirs = api.compile(folder, backend="gl").render(size=SIZE)
    # llvmpipe's LOD agrees with ours to 4.3e-6 of a level (measured), the bilinear lookups to a
    # few float32 ulps: after the lowp truncation at most one step of 2^-10 (texels are at most 1)
    assert np.abs(ours - theirs).max() <= 2.0**-10
    assert ours[..., :3].std() > 0.01


LOOKUPS = [
    "look(iChannel0, uv * 1.7)",  # a sampler passed to a helper
    "textureLod(iChannel0, uv, 0.0)",
    "textureProj(iChannel0, vec3(uv, 2.0))",
    "textureProj(iChannel0, vec4(uv, 0.0, 3.0))",
    "textureOffset(iChannel0, uv, ivec2(1, -1))",
    "texelFetchOffset(iChannel0, ivec2(fragCoord) % 8, 0, ivec2(1, 0))",
    "textureGrad(iChannel0, uv, vec2(0.01), vec2(0.01))",
    "vec4(vec2(textureSize(iChannel0, 0)), iChannelResolution[0].xy)",
    "textureLodOffset(iChannel0, uv, 0.0, ivec2(-1, 2))",
    "textureGradOffset(iChannel0, uv, vec2(0.01), vec2(0.01), ivec2(2, 0))",
    "textureProjOffset(iChannel0, vec3(uv, 1.5), ivec2(0, 1))",
    "textureProjLod(iChannel0, vec4(uv, 0.0, 0.7), 0.0)",
    "textureProjLodOffset(iChannel0, vec3(uv, 0.8), 0.0, ivec2(1, 1))",
    "textureProjGrad(iChannel0, vec3(uv, 1.2), vec2(0.01), vec2(0.01))",
    "textureProjGradOffset(iChannel0, vec4(uv, 0.0, 1.2), vec2(0.01), vec2(0.01), ivec2(-2, 0))",
]


@pytest.mark.parametrize("filt", ["nearest", "linear"])
@pytest.mark.parametrize("lookup", LOOKUPS)
def test_each_lookup_builtin_against_gl(gl, tmp_path, lookup, filt):
    _png(tmp_path / "tex.png", 7, 5, seed=4)
    body = f"""vec4 look(sampler2D s, vec2 uv) {{
    return texture(s, uv);
}}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {{
    vec2 uv = fragCoord / iResolution.xy * 1.3 - 0.1;
    fragColor = {lookup};
}}
"""
    folder = _folder(
        tmp_path,
        {"Image": body},
        {"Image": {"iChannel0": {"texture": "tex.png", "filter": filt, "wrap": "repeat"}}},
    )
    ours = api.compile(folder, backend="numpy").render(size=SIZE)
    theirs = api.compile(folder, backend="gl").render(size=SIZE)
    if filt == "nearest":
        assert np.array_equal(ours, theirs)
    else:  # see test_each_filter_and_wrap_against_gl
        assert np.abs(ours - theirs).max() <= 2.0**-10


def _export(tmp_path, image_inputs_extra=(), media="abc123.png"):
    """A Shadertoy JSON export of the feedback shader, its image in media/ beside it."""
    (tmp_path / "media").mkdir(exist_ok=True)
    _png(tmp_path / "media" / "abc123.png")
    sampler = {
        "filter": "linear",
        "wrap": "repeat",
        "vflip": "true",
        "srgb": "false",
        "internal": "byte",
    }
    buffer_in = {
        "id": 257,
        "src": "/media/previz/buffer00.png",
        "ctype": "buffer",
        "channel": 0,
        "sampler": {**sampler, "wrap": "clamp"},
        "published": 1,
    }
    tex_in = {
        "id": 30,
        "src": f"/media/a/{media}",
        "ctype": "texture",
        "channel": 1,
        "sampler": sampler,
    }
    data = {
        "Shader": {
            "ver": "0.1",
            "info": {"name": "feedback"},
            "renderpass": [
                {
                    "inputs": [buffer_in, tex_in],
                    "outputs": [{"id": 257, "channel": 0}],
                    "code": FEEDBACK,
                    "name": "Buffer A",
                    "type": "buffer",
                },
                {
                    "inputs": [
                        {**buffer_in, "sampler": {**sampler, "filter": "nearest"}},
                        {**tex_in, "sampler": {**sampler, "filter": "nearest"}},
                        *image_inputs_extra,
                    ],
                    "outputs": [{"id": 37, "channel": 0}],
                    "code": IMAGE,
                    "name": "Image",
                    "type": "image",
                },
            ],
        }
    }
    path = tmp_path / "shader.json"
    path.write_text(json.dumps(data))
    return str(path)


def test_shadertoy_json_export_verifies_over_frames(gl, tmp_path):
    path = _export(tmp_path)
    results = list(verify_frames(path, size=SIZE, frames=10))
    assert len(results) == 10 and all(r.match for r in results)
    # the same shader as a folder with channels.json renders the same pixels
    folder = tmp_path / "folder"
    folder.mkdir()
    _png(folder / "tex.png")
    _folder(
        folder,
        {"Buffer A": FEEDBACK, "Image": IMAGE},
        {
            "Buffer A": {
                "iChannel0": {"buffer": "Buffer A"},
                "iChannel1": {"texture": "tex.png", "filter": "linear"},
            },
            "Image": {
                "iChannel0": {"buffer": "Buffer A", "filter": "nearest"},
                "iChannel1": {"texture": "tex.png", "filter": "nearest", "wrap": "repeat"},
            },
        },
    )
    a = api.compile(path, backend="numpy").render(size=SIZE, frame=4, time=4 / 60)
    b = api.compile(str(folder), backend="numpy").render(size=SIZE, frame=4, time=4 / 60)
    assert np.array_equal(a, b)


@pytest.mark.parametrize(
    "extra, media, message",
    [
        (
            [{"id": 9, "src": "/presets/tex00.jpg", "ctype": "keyboard", "channel": 2}],
            "abc123.png",
            "the Image pass, iChannel2: keyboard inputs are not supported yet",
        ),
        ([], "nothere.png", "the Buffer A pass, iChannel1: no such file"),
    ],
)
def test_shadertoy_json_export_errors(tmp_path, extra, media, message):
    path = _export(tmp_path, extra, media)
    r = _cli("render", path, "-o", str(tmp_path / "o.png"))
    assert r.returncode == 2 and message in r.stderr and "Traceback" not in r.stderr, r.stderr


def test_shadertoy_json_export_errors_point_into_the_pass(tmp_path):
    path = _export(tmp_path)
    data = json.loads(open(path).read())
    data["Shader"]["renderpass"][1]["code"] = (
        "void mainImage(out vec4 c, in vec2 p) {\n  c = vec4(undefined_x);\n}\n"
    )
    open(path, "w").write(json.dumps(data))
    r = _cli("render", path, "-o", str(tmp_path / "o.png"))
    assert (
        r.returncode == 1
        and f"{path} [Image]:2:12: error: 'undefined_x' is not declared" in r.stderr
    )


def test_probe_refuses_channels_with_a_clear_error(feedback, tmp_path):
    r = _cli("probe", feedback, "--pixel", "3,3")
    assert r.returncode == 2 and "probe does not support buffers and channels yet" in r.stderr
    assert "Traceback" not in r.stderr


def test_lint_channel_uniforms_follow_the_uniform_rule(tmp_path):
    from glslcheck.lint import lint_paths

    text = """vec4 helper(sampler2D tex, vec2 uv)
{
    return texture(tex, uv);
}

vec4 direct(vec2 uv)
{
    return texture(iChannel1, uv);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy;
    fragColor = helper(iChannel0, uv) + direct(uv);
}
"""
    (tmp_path / "Image.glsl").write_text(text)
    found = [
        (f.loc.line, f.message)
        for f in lint_paths([tmp_path / "Image.glsl"]).findings
        if f.rule == "uniform-outside-mainimage"
    ]
    # the sampler passed in as a parameter is fine; iChannel1 read in the helper is flagged
    assert found == [(8, "the uniform 'iChannel1' is read in 'direct', not in mainImage")]


CHANNEL_TIME = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float used = texture(iChannel0, vec2(0.5)).x * 0.0 + texture(iChannel1, vec2(0.5)).a * 0.0;
    fragColor = vec4(iChannelTime[0], iChannelTime[1], iChannelTime[2] + used, iChannelTime[3] + \
        1.0);
}
"""


def channel_time_case(tmp_path):
    """A buffer on iChannel0 and an image on iChannel1, both read, each iChannelTime written out."""
    _png(tmp_path / "tex.png")
    return _folder(
        tmp_path,
        {
            "Buffer A": "void mainImage(out vec4 c, in vec2 p) { c = vec4(iTime); }\n",
            "Image": CHANNEL_TIME,
        },
        {"Image": {"iChannel0": {"buffer": "Buffer A"}, "iChannel1": {"texture": "tex.png"}}},
    )


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_channel_time_is_zero_for_images_and_buffers(gl, tmp_path, backend):
    # Shadertoy's page (its effect.js, Paint_Image) starts iChannelTime at 0 and sets it only for
    # video (currentTime), music (currentTime, or 10 + iTime when muted) and microphone inputs:
    # for images and buffers it stays 0 at every iTime. Rendered at iTime 3.0, frame 2.
    img = api.compile(channel_time_case(tmp_path), backend=backend).render(
        size=(8, 4), time=3.0, frame=2
    )
    assert np.array_equal(img, np.broadcast_to(np.float32([0.0, 0.0, 0.0, 1.0]), img.shape))


def test_shadertoy_json_export_older_buffer_names(tmp_path):
    # Older exports name the buffers "Buf A" .. "Buf D" (e.g. Shadertoy's MscXDn): "Buf C" is the
    # Buffer C tab, whatever the order of the passes in the file
    _export(tmp_path)
    data = json.loads((tmp_path / "shader.json").read_text())
    data["Shader"]["renderpass"][0]["name"] = "Buf C"
    data["Shader"]["renderpass"].reverse()
    (tmp_path / "old.json").write_text(json.dumps(data))
    from glslcheck.shadertoy.sources import load_shader

    shader = load_shader(str(tmp_path / "old.json"))
    assert set(shader.tabs) == {"Buffer C", "Image"}
    assert sorted((b.tab, b.channel, b.buffer) for b in shader.channels if b.buffer) == [
        ("Buffer C", 0, "Buffer C"),
        ("Image", 0, "Buffer C"),
    ]


def test_shadertoy_json_export_reads_an_unbound_channel_as_shadertoy_does(gl, tmp_path):
    # Shadertoy runs a pass that reads a channel with no input (a real public shader does, see
    # shadertoy/channels.py): the unit has no texture, so lookups give (0, 0, 0, 1) (textureSize of
    # such a unit is left undefined by ES 3.00: llvmpipe says 1x1, not pinned here)
    _export(tmp_path)
    data = json.loads((tmp_path / "shader.json").read_text())
    image = data["Shader"]["renderpass"][1]
    image["code"] = (
        "void mainImage(out vec4 c, in vec2 p) { c = textureLod(iChannel2, p / iResolution.xy, 0.0)"
        " + texelFetch(iChannel3, ivec2(0), 0) * 0.5 + 0.0 * texture(iChannel0, vec2(0.5)); }\n"
    )
    (tmp_path / "unbound.json").write_text(json.dumps(data))
    for backend in ("numpy", "gl"):
        img = api.compile(str(tmp_path / "unbound.json"), backend=backend).render(size=(8, 4))
        assert np.array_equal(img, np.broadcast_to(np.float32([0.0, 0.0, 0.0, 1.0]), img.shape)), (
            backend
        )


def test_a_shadertoy_json_export_of_one_pass_without_inputs_is_one_pass(tmp_path):
    """An Image pass with no inputs that reads no channel runs as the same code in a .glsl
    file does (one pass: verify's taint of undefined values and probe take it); one that reads
    a channel, even with nothing bound, or has inputs, still runs as passes."""
    from glslcheck.shadertoy.channels import needs_passes
    from glslcheck.shadertoy.sources import load_shader

    code = "void mainImage(out vec4 c, in vec2 p) { c = vec4(p / iResolution.xy, 0.5, 1.0); }\n"
    image = {"inputs": [], "outputs": [{"id": 37, "channel": 0}], "code": code}
    image.update(name="Image", type="image")
    data = {"Shader": {"ver": "0.1", "info": {"name": "one"}, "renderpass": [image]}}
    (tmp_path / "one.json").write_text(json.dumps(data))
    (tmp_path / "one.glsl").write_text(code)
    one = load_shader(str(tmp_path / "one.json"))
    assert one.channels == [] and not needs_passes(one)
    json_img = api.compile(str(tmp_path / "one.json"), backend="numpy").render(size=(8, 4))
    glsl_img = api.compile(str(tmp_path / "one.glsl"), backend="numpy").render(size=(8, 4))
    assert np.array_equal(json_img, glsl_img)
    image["code"] = code.replace("0.5, 1.0)", "0.5, 1.0) + texture(iChannel1, p)")
    (tmp_path / "reads.json").write_text(json.dumps(data))
    assert needs_passes(load_shader(str(tmp_path / "reads.json")))
    assert needs_passes(load_shader(_export(tmp_path)))


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
@pytest.mark.parametrize("size", [(15, 9), (9, 14)])
def test_odd_sizes_shade_helper_pixels_as_llvmpipe(gl, tmp_path, size):
    # An odd right or top edge: llvmpipe's 2x2 quads there take helper pixels outside the
    # viewport, which the derivatives and the implicit LOD read; the NumPy side renders the same
    # helper column/row (backends/numpy_engine/program.py render_tile). Without them these differed
    # by up to 0.56 (dFdy) and the implicit LOD picked other levels in the last row or column.
    _png(tmp_path / "tex.png", 70, 50, seed=5)
    body = f"""void mainImage(out vec4 fragColor, in vec2 fragCoord) {{
    {MIPMAP_UV}
    fragColor = texture(iChannel0, uv) + vec4(dFdx(fragCoord.x * fragCoord.x * 0.01),
                                              dFdy(fragCoord.y * fragCoord.y * 0.01), 0.0, 0.0);
}}
"""
    folder = _folder(tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png"}}})
    ours = api.compile(folder, backend="numpy").render(size=size)
    theirs = api.compile(folder, backend="gl").render(size=size)
    assert np.abs(ours - theirs).max() <= 2.0**-10  # as test_mipmap_against_gl


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
@pytest.mark.parametrize("filt", ["linear", "mipmap"])
@pytest.mark.parametrize("wrap", ["clamp", "repeat"])
@pytest.mark.parametrize(
    "lookup",
    [
        "texture(iChannel0, uv)",
        "texture(iChannel0, uv, fragCoord.x / 20.0 - 1.0)",  # a bias that differs within a quad
        "textureLod(iChannel0, uv, fragCoord.y / 9.0 - 0.5)",
        # a NaN LOD on some pixels (level 0, unblended: textures.lod_split)
        "textureLod(iChannel0, uv, fragCoord.x > 20.0 ? sqrt(-fragCoord.y) : fragCoord.y / 9.0)",
    ],
)
def test_filtering_bit_for_bit_on_a_ramp_of_scales(gl, tmp_path, lookup, wrap, filt):
    # A ramp of scales (0 to about 12 texels per pixel along x, LOD 0 to about 3.6) and
    # anisotropies on a texture whose sides are neither powers of two nor equal (the LOD's size
    # factor then rounds). The coordinates are exact in float32 on both backends (half-integers,
    # sums of small products, a power-of-two divisor). llvmpipe's lerps are fused multiply-adds
    # (LLVM's fmuladd) on a host with FMA, which the NumPy side copies (textures.py): equal bit
    # for bit there; elsewhere only to a few ulps (2^-10 after the lowp truncation).
    _png(tmp_path / "tex.png", 50, 70, seed=6)
    body = f"""void mainImage(out vec4 fragColor, in vec2 fragCoord) {{
    vec2 uv = vec2(fragCoord.x * fragCoord.x + fragCoord.y * 3.0,
                   fragCoord.y * fragCoord.y * 0.5 + fragCoord.x) / 512.0;
    fragColor = {lookup};
}}
"""
    folder = _folder(
        tmp_path,
        {"Image": body},
        {"Image": {"iChannel0": {"texture": "tex.png", "filter": filt, "wrap": wrap}}},
    )
    ours = api.compile(folder, backend="numpy").render(size=SIZE)
    theirs = api.compile(folder, backend="gl").render(size=SIZE)
    assert ours[..., :3].std() > 0.01
    if host_fma():  # llvmpipe fuses the lerps only where the CPU has FMA (driver_profile)
        assert np.array_equal(ours, theirs), (
            f"{int((ours != theirs).sum())} of {ours.size} values differ"
        )
    else:
        assert np.abs(ours - theirs).max() <= 2.0**-10


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
def test_implicit_lod_of_a_quad_with_a_nan_derivative(gl, tmp_path):
    # Two pixels of one 2x2 quad look up at x = +inf: the quad's x difference is inf - inf =
    # NaN, its y difference inf. llvmpipe's max (x86 maxps) keeps the inf and its fast_log2 of
    # the bits gives LOD 64: the last level for the whole quad (textures.py). np.maximum kept
    # the NaN, which gave level 0. The inf pixels themselves (their wrap of inf is the driver's
    # business) are left out of the comparison.
    _png(tmp_path / "tex.png", 16, 16, seed=7)
    body = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / 64.0;
    if (fragCoord.y < 1.0 && fragCoord.x > 30.0 && fragCoord.x < 32.0) uv.x = iResolution.x * \
        1e37 * 1e37;
    fragColor = texture(iChannel0, uv);
}
"""
    folder = _folder(tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png"}}})
    ours = api.compile(folder, backend="numpy").render(size=SIZE)
    theirs = api.compile(folder, backend="gl").render(size=SIZE)
    keep = np.ones(ours.shape[:2], bool)
    keep[-1, 30:32] = False  # images are top-down: GL's row 0 is the last
    assert np.abs(ours - theirs)[keep].max() <= 2.0**-10  # as test_mipmap_against_gl
    last = ours[-2, 30]  # the quad's upper pixels read the 1x1 last level, as llvmpipe
    assert (
        np.abs(last - ours[-2, 31]).max() <= 2.0**-10 and np.abs(last - ours[-2, 29]).max() > 0.01
    )


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
@pytest.mark.parametrize("filt", ["linear", "mipmap"])
def test_clamp_of_huge_infinite_and_nan_coordinates(gl, tmp_path, filt):
    # llvmpipe's CLAMP_TO_EDGE for linear filtering clamps the float coordinate before its
    # integer conversion (min(u * size, size); lp_build_sample_wrap_linear): 1e30 and inf read
    # the last texel, -1e30 and -inf the first. Converting first overflowed (1e30 read the first
    # texel, inf gave NaN). Both neighbours are one edge texel, so the result is exact whatever
    # the lerp's rounding. (A NaN coordinate still differs through the whole pipeline: not
    # emulated.)
    _png(tmp_path / "tex.png", 16, 16, seed=8)
    body = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float inf = iResolution.x * 1e37 * 1e37;
    float u[6] = float[6](1e30, -1e30, inf, -inf, 3e9, 1e20);
    fragColor = texture(iChannel0, vec2(u[int(fragCoord.x) % 6], u[int(fragCoord.y) % 6]));
}
"""
    folder = _folder(
        tmp_path,
        {"Image": body},
        {"Image": {"iChannel0": {"texture": "tex.png", "filter": filt, "wrap": "clamp"}}},
    )
    ours = api.compile(folder, backend="numpy").render(size=(12, 12))
    theirs = api.compile(folder, backend="gl").render(size=(12, 12))
    assert np.isfinite(theirs).all() and np.array_equal(ours, theirs)


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
@pytest.mark.parametrize("filt", ["nearest", "linear", "mipmap"])
@pytest.mark.parametrize("wrap", ["repeat", "clamp"])
@pytest.mark.parametrize("w, h", [(16, 16), (12, 10), (16, 10)])
def test_wrap_of_huge_and_infinite_coordinates_on_pot_and_npot_sizes(
    gl, tmp_path, w, h, wrap, filt
):
    # llvmpipe wraps each axis by its own formula (lp_build_sample_wrap_nearest / _linear),
    # chosen by whether level 0's size on that axis is a power of two (textures.py
    # _axis_nearest, _axis_linear): repeat on a power of two scales first (u * n - 0.5) and
    # masks the int32 index, so past 2^31 texels the index is INT_MIN & (n - 1) = 0; other sizes
    # take the fraction first; nearest clamp truncates to int32 (1e30 reads the *first* texel).
    # glslcheck took the fraction first everywhere (space_ship's exhaust noise, a
    # 256x256 repeat texture at coordinates near 1e7: 3 edge pixels over budget) and converted
    # nearest coordinates to int64. Offsets (textureOffset) go in before the repeat, in
    # normalised units on a size that is not a power of two. An infinite coordinate gives NaN
    # weights under linear repeat on both sides (NaN compares equal here).
    _png(tmp_path / "tex.png", w, h, seed=9)
    lookup = (
        "textureLodOffset(iChannel0, uv, 0.0, off)"
        if filt == "mipmap"
        else "textureOffset(iChannel0, uv, off)"
    )
    body = f"""void mainImage(out vec4 fragColor, in vec2 fragCoord) {{
    float inf = iResolution.x * 1e37 * 1e37;
    float u[8] = float[8](1e30, -1e30, inf, -inf, 3e9 + 0.7, 1.2e7 + 0.3, -7.77e5 - 0.1, 0.37);
    vec2 uv = vec2(u[int(fragCoord.x) % 8], u[int(fragCoord.y) % 8]) + fragCoord * vec2(0.013, \
        0.021);
    const ivec2 off = ivec2(-3, 5);
    if (fragCoord.x > 8.0) fragColor = texture(iChannel0, uv);
    else fragColor = {lookup};
}}
"""
    folder = _folder(
        tmp_path,
        {"Image": body},
        {"Image": {"iChannel0": {"texture": "tex.png", "filter": filt, "wrap": wrap}}},
    )
    ours = api.compile(folder, backend="numpy").render(size=(16, 16))
    theirs = api.compile(folder, backend="gl").render(size=(16, 16))
    assert np.array_equal(ours, theirs, equal_nan=True), (
        f"{int((ours != theirs).sum())} of {ours.size} values differ"
    )


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
def test_lowp_lookups_are_float16_rounded_towards_zero(gl, tmp_path):
    # A lowp lookup's result is float16 rounded towards zero (gallivm's float-to-half), not only
    # a 10-bit mantissa: a finite value past 65504 reads 65504 (elevated's Image pass unpacks a
    # velocity of about 5e5 from Buffer A's alpha: 387 pixels over tolerance when it read 5e5),
    # below 2^-14 a float16 subnormal (a multiple of 2^-24, truncated); inf and NaN stay.
    buf = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float inf = iResolution.x * 1e37 * 1e37;
    float v[12] = float[12](1e5, -7e4, 5e37, 65519.0, 65504.0, 1e-5, -3e-8, 1.6212e-6,
                            inf, -inf, 3.14159265, 6e-5);
    int i = int(fragCoord.x) % 12;
    fragColor = vec4(v[i], -v[i] * 0.5, v[i] * float(int(fragCoord.y) + 1), 1.0);
}
"""
    image = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    fragColor = texelFetch(iChannel0, ivec2(fragCoord), 0);
}
"""
    folder = _folder(
        tmp_path,
        {"Buffer A": buf, "Image": image},
        {"Image": {"iChannel0": {"buffer": "Buffer A"}}},
    )
    ours = api.compile(folder, backend="numpy").render(size=(12, 4))
    theirs = api.compile(folder, backend="gl").render(size=(12, 4))
    assert np.array_equal(ours, theirs, equal_nan=True), (
        f"{int((ours != theirs).sum())} of {ours.size} values differ"
    )
    assert (np.abs(theirs[np.isfinite(theirs)]) <= 65504).all() and (theirs == 65504).any()


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
@pytest.mark.parametrize(
    "lookup", ["texture(iChannel0, p)", "vec4(dFdx(p.x), dFdy(p.y), fwidth(p))"]
)
def test_derivatives_of_values_computed_under_a_branch(gl, tmp_path, lookup):
    # A function called under a varying `if` (elevated's cloud fbm in its sky branch): llvmpipe
    # computes its SSA values (`p = m * p` at the parameter's declaration level) in every lane
    # of a quad, the lanes outside the branch included, and a lookup's implicit LOD or a
    # derivative reads them. The NumPy backend kept those lanes' old `p` (a masked write):
    # boundary quads read another LOD (elevated: 25 sky pixels, up to 0.32). Now such writes
    # are unmasked (uniformity.py); a diagonal condition splits quads.
    _png(tmp_path / "tex.png", 64, 64, seed=10)
    body = f"""vec4 look(vec2 p) {{
    vec4 f = vec4(0.0);
    p = mat2(0.8, -0.6, 0.6, 0.8) * p * 2.02;
    f += {lookup};
    p = p * p * 1.7;
    f += {lookup};
    return f;
}}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {{
    vec2 uv = fragCoord * fragCoord / 800.0;
    fragColor = vec4(0.5);
    if (fragCoord.x + fragCoord.y > 20.0) fragColor = look(uv);
}}
"""
    folder = _folder(tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png"}}})
    ours = api.compile(folder, backend="numpy").render(size=(24, 16))
    theirs = api.compile(folder, backend="gl").render(size=(24, 16))
    assert (
        np.abs(ours - theirs).max() <= 2.0**-10
    )  # as test_mipmap_against_gl (exact on an FMA host)


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
@pytest.mark.parametrize("lod", ["0.0", "1.0", "fragCoord.x / 16.0"])
def test_an_integer_lod_reads_one_level(gl, tmp_path, lod):
    # lp_build_sample_mipmap filters the upper level only when some lane's LOD fraction is
    # above 0: with an integer LOD an infinite texel of the next level does not turn the result
    # into NaN (0 * inf), as the fused lerp with weight 0 would (textures.py _two_levels).
    buf = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    float inf = iResolution.x * 1e37 * 1e37;
    fragColor = vec4(fragCoord.x > 10.0 && fragCoord.y > 5.0 ? inf : fragCoord.x / 16.0, 0.5, \
        -inf, 1.0);
}
"""
    image = f"""void mainImage(out vec4 fragColor, in vec2 fragCoord) {{
    fragColor = textureLod(iChannel0, fragCoord / iResolution.xy, {lod});
}}
"""
    folder = _folder(
        tmp_path,
        {"Buffer A": buf, "Image": image},
        {"Image": {"iChannel0": {"buffer": "Buffer A", "filter": "mipmap"}}},
    )
    ours = api.compile(folder, backend="numpy", output="Image").render(size=(16, 8))
    theirs = api.compile(folder, backend="gl", output="Image").render(size=(16, 8))
    assert np.array_equal(ours, theirs, equal_nan=True), (
        f"{int((ours != theirs).sum())} of {ours.size} values differ"
    )


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
def test_arithmetic_on_lowp_lookups_is_float16(gl, tmp_path):
    # Mesa lowers GLSL's precision rules to float16 (glsl/lower_precision.cpp): an operation
    # whose operands are lowp lookups and constants runs in float16, each constant rounded to
    # float16 (nir_fold.lower_precision.lowp_tree). elephant's terrain, `2.1 +
    # 0.1*textureLod(..).x`, reads 2.130859375 where float32 gives 2.1319335: its raymarch stopped
    # elsewhere in 93 of 144 pixels of Buffer A at 16x9. Measured: float32 arithmetic equals
    # llvmpipe in 0-797 of the 2048 pixels of these expressions, float16 in all. A highp operand
    # (the variable `h`, iTime) keeps float32, and so does a `const` variable or a never-written
    # global (highp variables, unlike literals: alien_corridor's Buffer A mismatched when they
    # counted as constants); `rgb` stays as it is (a swizzled lookup alone is no operation).
    _png(tmp_path / "tex.png", 61, 37, seed=4)
    body = """const float K = 0.1;
float PI = 3.14159265;

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy * 0.37 + 0.01;
    float h = textureLod(iChannel0, uv, 0.0).x;
    vec4 a = vec4(2.1 + 0.1 * textureLod(iChannel0, uv, 0.0).x,
                  textureLod(iChannel0, uv, 0.0).x * texture(iChannel0, uv * 3.0).y - 1.7,
                  -texture(iChannel0, uv).z * 0.3 + 2.1,
                  texture(iChannel0, uv).w / 3.0 + 0.1);
    vec4 b = vec4(2.0 * texture(iChannel0, uv).rgb - 1.0, 2.1 + 0.1 * h + texture(iChannel0, \
        uv).y * iTime);
    vec4 c = vec4(K * texture(iChannel0, uv).x, PI * texture(iChannel0, uv).y, (2.0 * 0.05) * h, \
        0.0);
    fragColor = int(fragCoord.y) % 3 == 0 ? a : int(fragCoord.y) % 3 == 1 ? b : c;
}
"""
    folder = _folder(tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png"}}})
    ours = api.compile(folder, backend="numpy").render(size=(64, 32), time=0.7)
    theirs = api.compile(folder, backend="gl").render(size=(64, 32), time=0.7)
    assert np.array_equal(ours, theirs), (
        f"{int((ours != theirs).sum())} of {ours.size} values differ"
    )


@pytest.mark.usefixtures("llvmpipe")  # bit for bit with Mesa 22.3's llvmpipe
def test_the_square_of_a_lowp_lookup_is_float16(gl, tmp_path):
    # `pow(x, 2.0)` is x * x to NIR (fpow(a, 2.0) -> a * a), so on a lowp lookup it is one more
    # float16 operation of the tree (nir_fold.lower_precision._square), and a constant factor sinks
    # into it, `(x * #k) * x` (the square is used once): gargantua's Buffer A, `dustColor *=
    # pow(texture(iChannel1, ..).rgb, vec3(2.0)) * 4.0`, the first difference of its loop at
    # iteration 27 (1 pixel). Measured without it: 502, 500 and 512 of the 512 pixels differed
    # from llvmpipe (r, g, b); with x * x but the constant outside, 189 in b.
    _png(tmp_path / "tex.png", 61, 37, seed=5)
    body = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy * 0.37 + 0.01;
    fragColor = vec4(pow(texture(iChannel0, uv).rgb, vec3(2.0)) * 4.0, 1.0);
    fragColor.z = 0.5 - pow(texture(iChannel0, uv * 2.0).x, 2.0) * 3.7;
}
"""
    folder = _folder(tmp_path, {"Image": body}, {"Image": {"iChannel0": {"texture": "tex.png"}}})
    ours = api.compile(folder, backend="numpy").render(size=(32, 16))
    theirs = api.compile(folder, backend="gl").render(size=(32, 16))
    assert np.array_equal(ours, theirs), (
        f"{int((ours != theirs).sum())} of {ours.size} values differ"
    )
