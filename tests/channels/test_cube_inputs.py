"""Cube map inputs in channels.json (glslcheck/shadertoy/channels.py): the folder of six faces and
Shadertoy's six files, and every bad input as a located error with the file, never a traceback.
Sampling itself is measured against llvmpipe in tests/gl/test_cube_maps.py."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from glslcheck.backends import registry as api
from glslcheck.base.diagnostics import GlslError, InputError
from glslcheck.shadertoy.bindings import CUBE_FACES
from glslcheck.shadertoy.channels import ChannelInput, channel_uniforms, mip_levels

SKY = """void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 q = fragCoord / iResolution.xy * 2.0 - 1.0;
    fragColor = texture(iChannel0, vec3(q, 1.0)) + texture(iChannel0, vec3(1.0, q));
}
"""


def _face(path, n, value=None, h=None):
    texels = np.full((h or n, n, 4), 255, np.uint8)
    if value is not None:
        texels[..., 0] = value
    Image.fromarray(texels, "RGBA").save(path)


def _shader(tmp_path, spec, body=SKY):
    (tmp_path / "Image.glsl").write_text(body)
    (tmp_path / "channels.json").write_text(json.dumps({"Image": {"iChannel0": spec}}))
    return str(tmp_path)


def _folder(tmp_path, n=4, skip=None):
    sky = tmp_path / "sky"
    sky.mkdir()
    for k, name in enumerate(CUBE_FACES):
        if name != skip:
            _face(sky / f"{name}.png", n, value=40 * k)
    return sky


def _error(tmp_path, spec, body=SKY) -> str:
    with pytest.raises(InputError) as e:
        api.compile(_shader(tmp_path, spec, body), backend="numpy")
    return str(e.value)


def test_a_folder_of_faces_is_read_in_opengl_order(tmp_path):
    _folder(tmp_path)
    prog = api.compile(_shader(tmp_path, {"cubemap": "sky", "filter": "nearest"}), backend="numpy")
    chans = prog.impl._inputs("Image")
    cube = chans[0]
    assert cube.cube and cube.texels.shape == (6, 4, 4, 4)
    assert [round(float(cube.texels[k, 0, 0, 0]) * 255) for k in range(6)] == [
        40 * k for k in range(6)
    ]
    assert channel_uniforms(chans)["iChannelResolution"][0] == (4.0, 4.0, 1.0)


def test_shadertoy_s_six_files_are_read_as_the_faces(tmp_path):
    names = ["cube.png"] + [f"cube_{k}.png" for k in range(1, 6)]
    for k, name in enumerate(names):
        _face(tmp_path / name, 2, value=10 * k)
    prog = api.compile(_shader(tmp_path, {"cubemap": "cube.png"}), backend="numpy")
    cube = prog.impl._inputs("Image")[0]
    assert [round(float(cube.texels[k, 1, 1, 0]) * 255) for k in range(6)] == [
        10 * k for k in range(6)
    ]
    assert cube.filter == "mipmap" and cube.wrap == "clamp"  # Shadertoy's defaults


def test_a_cube_map_s_levels_are_each_face_s_pyramid():
    rng = np.random.default_rng(1)
    faces = rng.random((6, 8, 8, 4), dtype=np.float32)
    levels = ChannelInput(faces, "mipmap", cube=True).levels()
    assert [lv.shape for lv in levels] == [(6, 8, 8, 4), (6, 4, 4, 4), (6, 2, 2, 4), (6, 1, 1, 4)]
    for k in range(6):
        for lv, own in zip(levels, mip_levels(faces[k])):
            assert np.array_equal(lv[k], own)


@pytest.mark.parametrize(
    "case, spec, needle",
    [
        ("missing face", {"cubemap": "sky"}, "no nz face in the folder"),
        ("no such folder", {"cubemap": "nowhere"}, "no such file or folder"),
        ("repeat wrap", {"cubemap": "sky", "wrap": "repeat"}, 'only "clamp" applies'),
        ("outside", {"cubemap": "../sky"}, "outside the shader's folder"),
    ],
)
def test_bad_cube_maps_are_errors_naming_the_key(tmp_path, case, spec, needle):
    shader_dir = tmp_path / "shader"
    shader_dir.mkdir()
    _folder(shader_dir, skip="nz" if case == "missing face" else None)
    if case == "outside":
        _folder(tmp_path)
    message = _error(shader_dir, spec)
    assert needle in message and '"Image"."iChannel0"' in message, message
    assert "channels.json" in message


def test_faces_of_different_sizes_name_both_files(tmp_path):
    sky = _folder(tmp_path)
    _face(sky / "py.png", 8)
    message = _error(tmp_path, {"cubemap": "sky"})
    assert "py.png' is 8x8" in message and "px.png' is 4x4" in message, message


def test_a_face_that_is_not_square_is_an_error(tmp_path):
    sky = _folder(tmp_path)
    _face(sky / "nx.png", 4, h=3)
    assert "nx.png' is 4x3, not square" in _error(tmp_path, {"cubemap": "sky"})


def test_a_missing_shadertoy_face_file_is_named(tmp_path):
    for name in ["cube.png", "cube_1.png", "cube_2.png", "cube_4.png", "cube_5.png"]:
        _face(tmp_path / name, 2)
    assert "cube_3.png" in _error(tmp_path, {"cubemap": "cube.png"})


def test_a_cube_map_sampled_in_2d_is_a_located_error(tmp_path):
    _folder(tmp_path)
    body = "void mainImage(out vec4 c, in vec2 p) { c = texture(iChannel0, p / 8.0); }\n"
    with pytest.raises(GlslError) as e:
        api.compile(_shader(tmp_path, {"cubemap": "sky"}, body), backend="numpy")
    (d,) = e.value.diagnostics
    assert "bound to a cube map but not sampled as one" in d.message
    assert (d.loc.line, d.loc.column) == (1, body.index("iChannel0") + 1)


def test_an_image_sampled_as_a_cube_map_is_a_located_error(tmp_path):
    _face(tmp_path / "tex.png", 4)
    with pytest.raises(GlslError) as e:
        api.compile(_shader(tmp_path, {"texture": "tex.png"}), backend="numpy")
    assert all("sampled as a cube map" in d.message for d in e.value.diagnostics)


def test_the_cli_reports_a_bad_cube_map_without_a_traceback(tmp_path):
    sky = _folder(tmp_path)
    _face(sky / "pz.png", 2)
    out = tmp_path / "out.png"
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "glslcheck",
            "render",
            _shader(tmp_path, {"cubemap": "sky"}),
            "-o",
            str(out),
        ],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 2, run.stderr
    assert "Traceback" not in run.stderr and "pz.png" in run.stderr
    assert not out.exists()


def _export(tmp_path, src="/media/a/sky.png", wrap="repeat"):
    inputs = [
        {
            "id": 4,
            "src": src,
            "ctype": "cubemap",
            "channel": 0,
            "sampler": {"filter": "mipmap", "wrap": wrap, "vflip": "false", "srgb": "false"},
        }
    ]
    data = {
        "Shader": {
            "info": {"name": "sky"},
            "renderpass": [
                {"inputs": inputs, "outputs": [], "code": SKY, "name": "Image", "type": "image"}
            ],
        }
    }
    (tmp_path / "shader.json").write_text(json.dumps(data))
    return str(tmp_path / "shader.json")


def test_a_shadertoy_export_reads_its_media_cube_map(tmp_path):
    # Shadertoy's export names the first face; the other five are name_1 .. name_5 beside it.
    # Its wrap is not applied (seamless filtering), as in a folder's channels.json
    media = tmp_path / "media"
    media.mkdir()
    names = ["sky.png"] + [f"sky_{k}.png" for k in range(1, 6)]
    for k, name in enumerate(names):
        _face(media / name, 4, value=30 * k)
    from_export = api.compile(_export(tmp_path), backend="numpy").render(size=(16, 8))
    folder = tmp_path / "folder"
    folder.mkdir()
    for k, name in enumerate(CUBE_FACES):
        _face(folder / f"{name}.png", 4, value=30 * k)
    from_folder = api.compile(_shader(folder, {"cubemap": "."}), backend="numpy").render(
        size=(16, 8)
    )
    assert np.array_equal(from_export, from_folder)
    (media / "sky_3.png").unlink()
    with pytest.raises(InputError, match="sky_3.png"):
        api.compile(_export(tmp_path), backend="numpy")


def test_a_shadertoy_export_reading_the_cube_a_pass_is_not_supported_yet(tmp_path):
    with pytest.raises(InputError, match="Cube A pass's cube map is not supported yet"):
        api.compile(_export(tmp_path, "/media/previz/cubemap00.png"), backend="numpy")
