"""Reading shaders: tab names, folders, plain GLSL files, encodings, and I/O errors (exit 2)."""

from __future__ import annotations

import os

import pytest

from glslcheck.base.diagnostics import InputError
from glslcheck.cli.main import main
from glslcheck.shadertoy.sources import (
    _parent,
    find_shaders,
    folder_entries,
    load_shader,
    looks_like_shader,
    name_says_shader,
    path_name,
    path_stem,
    path_suffix,
    posix_path,
    read_source,
    tab_name,
)


@pytest.mark.parametrize(
    "name,tab",
    [
        ("Image.glsl", "Image"),
        ("image", "Image"),
        ("IMAGE.FRAG", "Image"),
        ("Common.txt", "Common"),
        ("Buffer A.glsl", "Buffer A"),
        ("buffer_a.glsl", "Buffer A"),
        ("buffer-b.frag", "Buffer B"),
        ("BufferD", "Buffer D"),
        ("Cube A.glsl", "Cube A"),
        ("sound.glsl", "Sound"),
        ("spheres.glsl", None),
        # what students add to a tab's name in real course repositories
        ("Common Tab.txt", "Common"),
        ("Image Tab.txt", "Image"),
        ("Buffer A (Rotating Cube Map + Lambert).txt", "Buffer A"),
        ("Buffer C (FIREBENDING).txt", "Buffer C"),
        ("notes (old).txt", None),
        ("kebab.txt", None),
        ("tab.txt", None),
    ],
)
def test_tab_names(name, tab):
    assert tab_name(name) == tab


def test_folder_of_tabs_and_common_first(tmp_path):
    (tmp_path / "Image.glsl").write_text(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(g()); }\n"
    )
    (tmp_path / "common.glsl").write_text("float g() { return 1.0; }\n")
    (tmp_path / "notes.md").write_text("not a shader")
    shader = load_shader(tmp_path)
    assert sorted(shader.tabs) == ["Common", "Image"]
    assert [s.tab for s in shader.units_for("Image")] == ["Common", "Image"]


def test_image_file_picks_up_sibling_common(tmp_path):
    (tmp_path / "Image.glsl").write_text(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(g()); }\n"
    )
    (tmp_path / "Common.glsl").write_text("float g() { return 1.0; }\n")
    shader = load_shader(tmp_path / "Image.glsl")
    assert [s.tab for s in shader.units_for("Image")] == ["Common", "Image"]


# names of real GPR-200 repositories' Lab 6 tabs (the texts are ours)
@pytest.mark.parametrize(
    "image, common",
    [
        ("Lab06Image.txt", "Lab06Common.txt"),
        ("Lab 6.txt", "Lab 6 Common.txt"),
        ("midTermBufA.txt", "midTermCommon.txt"),
        ("shadertoy_midterm_bufferA.txt", "shadertoy_midterm_common_tab.txt"),
        ("GPR-200 Midterm (Buffer A).txt", "GPR-200 Midterm (Common).txt"),
        ("bufferB_lab6_name .txt", "common_lab6_name.txt"),
    ],
)
def test_pass_file_picks_up_the_common_named_for_it(tmp_path, image, common):
    (tmp_path / image).write_text("void mainImage(out vec4 c, in vec2 f) { c = vec4(g()); }\n")
    (tmp_path / common).write_text("float g() { return 1.0; }\n")
    (tmp_path / "Lab05Common.txt").write_text("float h() { return 2.0; }\n")
    shader = load_shader(tmp_path / image)
    assert [s.tab for s in shader.units_for("Image")] == ["Common", "Image"]
    assert shader.common is not None and shader.common.path.endswith(common)
    walked = {s.root: sorted(s.tabs) for s in find_shaders([str(tmp_path)])}
    assert walked[str(tmp_path / image)] == ["Common", "Image"]
    assert walked[str(tmp_path / common)] == ["Common"]  # linted as the Common tab it is


def test_a_folder_of_tabs_named_with_tab_and_descriptions(tmp_path):
    # a real Fall 2020 midterm's layout (names only; the texts are ours)
    (tmp_path / "Image Tab.txt").write_text(
        "void mainImage(out vec4 c, in vec2 f) { c = texture(iChannel0, f) * g(); }\n"
    )
    (tmp_path / "Buffer A (Rotating Cube Map + Lambert).txt").write_text(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(g()); }\n"
    )
    (tmp_path / "Buffer B.txt").write_text(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(g()); }\n"
    )
    (tmp_path / "Common Tab.txt").write_text("float g() { return 1.0; }\n")
    shader = load_shader(tmp_path)
    assert sorted(shader.tabs) == ["Buffer A", "Buffer B", "Common", "Image"]
    alone = load_shader(tmp_path / "Buffer B.txt")
    assert alone.common is not None and alone.common.path.endswith("Common Tab.txt")


def test_a_common_named_for_no_pass_is_not_picked_up(tmp_path):
    (tmp_path / "Lab06Image.txt").write_text(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }\n"
    )
    (tmp_path / "Lab05Common.txt").write_text("float h() { return 2.0; }\n")
    assert sorted(load_shader(tmp_path / "Lab06Image.txt").tabs) == ["Image"]


def test_a_common_named_first_for_another_project_is_not_picked_up(tmp_path):
    (tmp_path / "bufferB_lab6_name.txt").write_text(
        "void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }\n"
    )
    (tmp_path / "common_lab5_name.txt").write_text("float h() { return 2.0; }\n")
    (tmp_path / "commonplace.txt").write_text("float h() { return 2.0; }\n")
    assert sorted(load_shader(tmp_path / "bufferB_lab6_name.txt").tabs) == ["Image"]


def test_two_files_for_one_tab_is_an_error(tmp_path):
    (tmp_path / "Image.glsl").write_text("x")
    (tmp_path / "image.frag").write_text("y")
    with pytest.raises(InputError, match="second file for the Image tab"):
        load_shader(tmp_path)


def test_plain_glsl_file_is_taken_as_is(tmp_path):
    p = tmp_path / "Image.glsl"
    p.write_text(
        "#version 300 es\nprecision highp float;\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n"
    )
    assert read_source(p).is_plain_glsl


def test_bom_crlf_and_lone_cr_keep_lines(tmp_path):
    p = tmp_path / "Image.glsl"
    p.write_bytes(b"\xef\xbb\xbf// a\r\nfloat x;\rfloat y;\n")
    assert read_source(p).text == "// a\nfloat x;\nfloat y;\n"


def test_non_utf8_names_line_and_column(tmp_path):
    p = tmp_path / "Image.glsl"
    p.write_bytes(b"// ok\n// caf\xe9\n")
    with pytest.raises(InputError) as info:
        read_source(p)
    assert f"{p}:2:7: error: the file is not UTF-8" in str(info.value)


def test_walk_finds_loose_files_and_tab_folders(tmp_path):
    (tmp_path / "a.glsl").write_text("x")
    (tmp_path / "part").mkdir()
    (tmp_path / "part" / "Image.glsl").write_text("y")
    shaders = find_shaders([str(tmp_path)])
    assert len(shaders) == 2


@pytest.mark.parametrize("command", ["parse", "check", "lint"])
def test_missing_file_exits_2_without_traceback(command, tmp_path, capsys):
    assert main([command, str(tmp_path / "nope.glsl")]) == 2
    err = capsys.readouterr().err
    assert "no such file" in err and "Traceback" not in err


def test_unreadable_file_exits_2(tmp_path, capsys, monkeypatch):
    # As root (CI) chmod 0 does not stop a read, so the OS error is simulated at os.open()
    # (read_source opens with os.open, O_NONBLOCK, so a FIFO is refused instead of waited on).
    p = tmp_path / "Image.glsl"
    p.write_text("x")
    real_open = os.open

    def deny(file, *args, **kwargs):
        if str(file) == str(p):
            raise PermissionError(13, "Permission denied", str(file))
        return real_open(file, *args, **kwargs)

    monkeypatch.setattr(os, "open", deny)
    assert main(["parse", str(p)]) == 2
    assert "permission denied" in capsys.readouterr().err


def test_binary_file_exits_2(tmp_path, capsys):
    p = tmp_path / "Image.glsl"
    p.write_bytes(bytes(range(256)))
    assert main(["parse", str(p)]) == 2
    assert "not UTF-8" in capsys.readouterr().err


def test_parse_cli_exit_codes_and_output(tmp_path, capsys):
    good = tmp_path / "good.glsl"
    good.write_text("void mainImage(out vec4 c, in vec2 f) { c = vec4(1.0); }\n")
    bad = tmp_path / "bad.glsl"
    bad.write_text("void mainImage(out vec4 c, in vec2 f) {\n    c = vec4(1.0)\n}\n")
    assert main(["parse", str(good)]) == 0
    assert main(["parse", "--print", str(good)]) == 0
    assert "c = vec4(1.0);" in capsys.readouterr().out
    assert main(["parse", "--ast", str(good)]) == 0
    assert "FunctionDefinition" in capsys.readouterr().out
    assert main(["parse", str(good), str(bad)]) == 1
    err = capsys.readouterr().err
    assert f"{bad}:2:18: error: expected ';' after this statement" in err
    assert "    c = vec4(1.0)\n" in err and "^" in err
    assert main(["parse"]) == 2
    assert main(["frobnicate"]) == 2


@pytest.mark.parametrize(
    "path",
    [
        "",
        ".",
        "./",
        "/",
        "//",
        "///",
        "//a",
        "///a/b",
        "a/./b",
        "a//b/",
        "a/../b",
        "./x.glsl",
        "x.",
        ".x",
        "..x",
        "a.b.glsl",
        "dir/.hidden",
        "Buffer A.txt",
        "a/b/",
        "..",
        "../",
        "x/..",
        "lab 4/Image",
    ],
)
def test_path_helpers_spell_paths_as_pathlib_does(path):
    """The lint path spells paths without pathlib (importing it costs start-up time); every message
    must name a path as the pathlib code before it did."""
    from pathlib import PurePosixPath

    p = PurePosixPath(path)
    assert posix_path(path) == str(p)
    assert (path_name(path), path_suffix(path), path_stem(path)) == (p.name, p.suffix, p.stem)
    assert _parent(posix_path(path)) == str(p.parent)


def test_folder_entries_are_sorted_iterdir(tmp_path, monkeypatch):
    from pathlib import Path

    for name in ("b.glsl", "A.glsl", "a-b", "a", ".hidden", "Image.txt"):
        (tmp_path / name).write_text("")
    monkeypatch.chdir(tmp_path)
    assert folder_entries(".") == [str(p) for p in sorted(Path(".").iterdir())]
    assert folder_entries(str(tmp_path)) == [str(p) for p in sorted(tmp_path.iterdir())]


# --- which .txt and extension-less files are shaders: their text decides ------------------

SHADER_TEXT = """\
// Lab 4.txt: spheres lit by one point light
struct PointLight { vec3 center; vec3 color; float intensity; };

// the light above and to the right of the viewer
const vec3 kLight = vec3(1.0, 1.0, -1.0);
"""


@pytest.mark.parametrize(
    "text",
    [
        SHADER_TEXT,
        "void mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n    fragColor = vec4(1.0);\n}\n",
        "float sq(float x) { return x * x; }\n",  # a Common tab: declarations only
        "#define PI 3.14159\n",
        # a short note above the code, uncommented: still mostly code
        "Lab 4 by Ana Ruiz and Ben Li\nvoid mainImage(out vec4 c, in vec2 p)\n"
        "{\n    c = vec4(p, 0.0, 1.0);\n}\n",
    ],
)
def test_shader_texts_are_shaders(text):
    assert looks_like_shader(text)


@pytest.mark.parametrize(
    "text",
    [
        "",
        "plain notes\n",
        "Lab 4 notes: we did the lights together, then the spheres.\nThe float values are fine.\n",
        # Markdown with a shader in a fence: a README, never parsed as GLSL
        "# Lab 4\n```glsl\nvoid mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n```\n",
        # prose that mentions a declaration once
        "To make it work we wrote\nfloat d = length(p);\nbut then we changed our minds about the\n"
        "way the lights should attenuate over the distance from the surface to the light.\n",
        "// only a comment: void mainImage(out vec4 c, in vec2 p) {}\n",
        "vec3 x;\0binary",
        "all: build\n\tcc -o lab main.c\n",  # a Makefile
    ],
)
def test_other_texts_are_not_shaders(text):
    assert not looks_like_shader(text)


@pytest.mark.parametrize(
    "name,says",
    [
        ("Image.txt", True),
        ("lab4/buffer_a", True),
        ("x.glsl", True),
        ("Lab 4.txt", None),
        ("code", None),
        ("README.txt", False),
        ("LICENSE", False),
        ("readme", False),
        ("notes.md", False),
        (".hidden.txt", False),
    ],
)
def test_what_a_name_says(name, says):
    assert name_says_shader(name) is says


def test_walk_takes_txt_files_by_their_text(tmp_path):
    course = tmp_path / "course"
    for name in ("Lab 4.txt", "Lab4/Lab4.txt", "GPRO-Graphics-Lab4/main.txt", "code"):
        (course / name).parent.mkdir(parents=True, exist_ok=True)
        (course / name).write_text(SHADER_TEXT)
    (course / "notes.txt").write_text("We split the work: Ana the spheres, Ben the lights.\n")
    (course / "README.txt").write_text(SHADER_TEXT)  # a README by its name
    (course / "Makefile").write_text("all: build\n")
    roots = sorted(os.path.relpath(s.root, course) for s in find_shaders([str(course)]))
    assert roots == ["GPRO-Graphics-Lab4/main.txt", "Lab 4.txt", "Lab4/Lab4.txt", "code"]
