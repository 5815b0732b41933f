"""Hostile JSON (Shadertoy exports with fields of the wrong type, channels.json nested past the
JSON reader's depth) and file names that are not UTF-8: each is a clear message naming the file
(and the JSON field), exit 2, or a report with the name escaped; never a traceback.
"""

from __future__ import annotations

import copy
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from glslcheck.base.diagnostics import InputError
from glslcheck.shadertoy.sources import load_shadertoy_json

ROOT = Path(__file__).resolve().parents[2]
IMAGE = (
    "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n"
    "{\n    float unused_x = 1.0;\n    fragColor = vec4(1.0);\n}\n"
)
EXPORT = {
    "Shader": {
        "renderpass": [
            {
                "code": IMAGE.replace("unused_x", "a"),
                "name": "Buffer A",
                "type": "buffer",
                "inputs": [],
                "outputs": [{"id": 257, "channel": 0}],
            },
            {
                "code": IMAGE,
                "name": "Image",
                "type": "image",
                "inputs": [
                    {
                        "id": 257,
                        "ctype": "buffer",
                        "channel": 0,
                        "src": "/media/previz/buffer00.png",
                        "sampler": {"filter": "linear", "wrap": "clamp", "vflip": "true"},
                    }
                ],
                "outputs": [{"id": 37, "channel": 0}],
            },
        ]
    }
}


def _cli(*args, cwd=None, env=None, timeout=120):
    env = {**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}
    return subprocess.run(
        [sys.executable, "-m", "glslcheck", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        timeout=timeout,
    )


def _set(data, path, value):
    """`data` with the field at `path` (keys and indices below "Shader") set to `value`."""
    data = copy.deepcopy(data)
    node = data["Shader"]
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    return data


def test_the_export_used_below_loads(tmp_path):
    path = tmp_path / "shader.json"
    path.write_text(json.dumps(EXPORT))
    shader = load_shadertoy_json(path)
    assert sorted(shader.tabs) == ["Buffer A", "Image"] and len(shader.channels) == 1


@pytest.mark.parametrize(
    "field, value, where",
    [
        (("renderpass", 1), "void mainImage", "Shader.renderpass[1]"),
        (("renderpass", 1, "code"), 5, "Shader.renderpass[1].code"),
        (("renderpass", 1, "type"), ["image"], "Shader.renderpass[1].type"),
        (("renderpass", 0, "name"), {"a": 1}, "Shader.renderpass[0].name"),
        (("renderpass", 0, "outputs"), 257, "Shader.renderpass[0].outputs"),
        (("renderpass", 0, "outputs", 0), "257", "Shader.renderpass[0].outputs[0]"),
        (("renderpass", 1, "inputs"), {"channel": 0}, "Shader.renderpass[1].inputs"),
        (("renderpass", 1, "inputs", 0), 5, "Shader.renderpass[1].inputs[0]"),
        (("renderpass", 1, "inputs", 0, "channel"), "0", "Shader.renderpass[1].inputs[0].channel"),
        (("renderpass", 1, "inputs", 0, "channel"), True, "Shader.renderpass[1].inputs[0].channel"),
        (("renderpass", 1, "inputs", 0, "channel"), 0.0, "Shader.renderpass[1].inputs[0].channel"),
        (
            ("renderpass", 1, "inputs", 0, "ctype"),
            ["buffer"],
            "Shader.renderpass[1].inputs[0].ctype",
        ),
        (
            ("renderpass", 1, "inputs", 0, "sampler"),
            "linear",
            "Shader.renderpass[1].inputs[0].sampler",
        ),
        (("renderpass", 1, "inputs", 0, "src"), 3, "Shader.renderpass[1].inputs[0].src"),
    ],
)
def test_an_export_field_of_the_wrong_type_is_named(tmp_path, field, value, where):
    path = tmp_path / "shader.json"
    path.write_text(json.dumps(_set(EXPORT, field, value)))
    with pytest.raises(InputError) as e:
        load_shadertoy_json(path)
    assert str(e.value).startswith(f"{path}: error: {where}"), str(e.value)


def test_an_export_field_of_the_wrong_type_exits_2(tmp_path):
    path = tmp_path / "shader.json"
    path.write_text(json.dumps(_set(EXPORT, ("renderpass", 1, "inputs", 0, "sampler"), "linear")))
    done = _cli("check", str(path))
    err = done.stderr.decode()
    assert done.returncode == 2 and "Traceback" not in err, err
    assert (
        f"{path}: error: Shader.renderpass[1].inputs[0].sampler: must be an object, not a string"
        in err
    )


def _deep(depth: int = 100_000) -> str:
    return "[" * depth + "]" * depth


def test_a_deeply_nested_channels_json_is_named(tmp_path):
    (tmp_path / "Image.glsl").write_text(IMAGE)
    (tmp_path / "channels.json").write_text(_deep())
    done = _cli("render", str(tmp_path), "--size", "4x4", "-o", str(tmp_path / "out.png"))
    err = done.stderr.decode()
    assert done.returncode == 2 and "Traceback" not in err, err
    assert f"{tmp_path / 'channels.json'}: error: too deeply nested JSON" in err
    assert not (tmp_path / "out.png").exists()


def test_a_deeply_nested_export_is_named(tmp_path):
    path = tmp_path / "shader.json"
    path.write_text('{"Shader": ' + _deep() + "}")
    done = _cli("check", str(path))
    err = done.stderr.decode()
    assert done.returncode == 2 and "Traceback" not in err, err
    assert f"{path}: error: too deeply nested JSON" in err


STRICT = {"PYTHONIOENCODING": "utf-8:strict"}


@pytest.fixture
def undecodable(tmp_path):
    """A shader folder whose name holds the byte 0xff (not UTF-8), with lint findings in it."""
    folder = tmp_path / os.fsdecode(b"sh\xff")
    folder.mkdir()
    (folder / "Image.glsl").write_text(IMAGE)
    return folder


@pytest.mark.parametrize("fmt", ["text", "json", "sarif", "github"])
def test_lint_reports_a_name_that_is_not_utf8_on_a_strict_stdout(undecodable, fmt):
    done = _cli("lint", "--format", fmt, undecodable.name, cwd=undecodable.parent, env=STRICT)
    err = done.stderr.decode(errors="replace")
    assert done.returncode == 1 and "Traceback" not in err, err
    out = done.stdout.decode("utf-8")  # strict: the report is valid UTF-8
    if fmt in ("json", "sarif"):
        out = json.loads(out)
    if fmt == "json":
        assert out["findings"][0]["path"] == "sh\\udcff/Image.glsl"
    elif fmt == "sarif":
        uri = out["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"][
            "uri"
        ]
        assert uri == "sh%FF/Image.glsl"
    else:
        assert "sh\\udcff/Image.glsl" in out


@pytest.mark.parametrize("fmt", ["json", "sarif", "github"])
def test_lint_writes_a_name_that_is_not_utf8_to_its_output_file(undecodable, fmt):
    out = undecodable.parent / f"report.{fmt}"
    done = _cli("lint", "--format", fmt, undecodable.name, "-o", out.name, cwd=undecodable.parent)
    err = done.stderr.decode(errors="replace")
    assert done.returncode == 1 and "Traceback" not in err, err
    text = out.read_text(encoding="utf-8")  # strict: the report is valid UTF-8
    expected = {
        "json": '"sh\\\\udcff/Image.glsl"',
        "sarif": '"sh%FF/Image.glsl"',
        "github": "sh\\udcff/Image.glsl",
    }
    assert expected[fmt] in text


def test_verify_prints_a_name_that_is_not_utf8_on_a_strict_stdout(undecodable, gl):
    done = _cli("verify", undecodable.name, "--size", "4x4", cwd=undecodable.parent, env=STRICT)
    err = done.stderr.decode(errors="replace")
    assert done.returncode == 0 and "Traceback" not in err, err
    assert "sh\\udcff" in done.stdout.decode("utf-8")
