"""The engine's parts: the text scan, header wordings, and how an AST rule plugs in."""

from __future__ import annotations

import types

import pytest
from hypothesis import given
from hypothesis import strategies as st

from glslcheck.base.diagnostics import Diagnostic
from glslcheck.lint import engine, lint_source
from glslcheck.lint.rules import Rule, all_rules
from glslcheck.lint.rules.missing_header import (
    contributors,
    named_students,
    names_file,
    states_purpose,
)
from glslcheck.lint.textscan import scan
from glslcheck.shadertoy.sources import Source


def kinds(text: str) -> list[str]:
    return [str(k) for k in scan(text).line_kinds]


def test_line_kinds():
    text = (
        "// comment\n"
        "\n"
        "x = 1; // trailing\n"
        "/* leading */ y = 2;\n"
        "/* block\n"
        "   still */ z = 3;\n"
        "};\n"
        "{ // per light\n"
        "#define A 1\n"
        "w = 1; // glslcheck: ignore[missing-comment]\n"
        "// glslcheck: ignore-file[missing-credit]\n"
        "   \n"
    )
    assert kinds(text) == [
        "comment",
        "blank",
        "trailing",
        "leading",
        "comment",
        "leading",
        "brace",
        "brace-comment",
        "code",
        "code",
        "directive",
        "blank",
    ]


def test_comments_and_blanked_code():
    s = scan("a = 1; /* b\nc */ d; // e\n")
    assert [(c.text, c.line, c.column, c.end_line, c.end_column, c.block) for c in s.comments] == [
        (" b\nc ", 1, 8, 2, 5, True),
        (" e", 2, 9, 2, 13, False),
    ]
    assert s.code_lines == ["a = 1;     ", "     d;     "]


def test_line_continuation_in_line_comment():
    assert kinds("// goes on \\\nstill comment\ncode;\n") == ["comment", "comment", "code"]


def test_unterminated_block_comment():
    s = scan("x;\n/* never closed\nmore\n")
    assert kinds("x;\n/* never closed\nmore\n") == ["code", "comment", "comment"]
    assert s.comments[-1].end_line == 3


@given(st.text(alphabet="ab /*{};\n\\#\t", max_size=80))
def test_scan_keeps_every_line_and_column(text):
    s = scan(text)
    assert len(s.line_kinds) == len(s.lines) == len(s.code_lines)
    assert [len(c) for c in s.code_lines] == [len(line) for line in s.lines]


@pytest.mark.parametrize(
    "header",
    [
        "File: Image\nPurpose: lit spheres\nAuthors: Ana: lighting",
        "@file Image.glsl\n@brief lit spheres\n@author Ana Ruiz (lighting)",
        " * Image tab - draws the scene\n * Modified by Ben Li: added Blinn-Phong",
        "Filename: image.glsl\nThis shader draws lit spheres.\nContributors:\n  Ana - "
        "lighting\n  Ben - comments",
    ],
)
def test_header_wordings_accepted(header):
    assert names_file(header, "lab/Image.glsl", "Image")
    assert states_purpose(header, "lab/Image.glsl", "Image")
    assert contributors(header) == "ok"


@pytest.mark.parametrize(
    "header, expected",
    [
        ("Authors: Ana Ruiz, Ben Li", "bare"),
        ("By Ana and Ben", "bare"),
        ("Written by Madeline Cody", "ok"),  # one author did all of it: no role list to give
        (
            "Copyright 2020 Ana Ruiz and Ben Li\nAuthors:\n  Ana Ruiz (lighting)\n  Ben Li "
            "(comments)",
            "ok",
        ),
        ("Copyright 2020 Dan Buckstein\nCopyright 2020 Ana Ruiz", "ok"),  # the license names her
        ("Lab 4 lighting", "none"),
        ("Authors:\n\nAna: lighting", "none"),
    ],
)
def test_contributor_lists(header, expected):
    assert contributors(header) == expected


@pytest.mark.parametrize(
    "header, expected",
    [
        (
            "GLSL STARTER CODE BY DANIEL S. BUCKSTEIN\nModification Author: Shakeem Brown",
            ["Shakeem Brown"],
        ),
        ("Lead author - Ana Ruiz", ["Ana Ruiz"]),
        (
            "This assignment was written by Dylan Rubin. Sources used are credited below.",
            ["Dylan Rubin"],
        ),
        ("Written by J. R. Smith", ["J. R. Smith"]),  # initials are no sentence end
        ("Modification Title: Intro to Textures & Image Processing", []),
        ("Lab Author notes: see the bottom", []),  # no label: words follow the qualifier
        ("Shaded by Phong. Lighting Model notes", []),  # the sentence after is no name either
    ],
)
def test_named_students(header, expected):
    assert named_students(header) == expected


# The course's header template: its fields below the author are no contributors.
_TEMPLATE = (
    "Author: Ana Ruiz\nClass: GPR-200-01\nAssignment: Lab 4: Lighting\n"
    "Date Assigned: 09/25/2020\nDue Date: 10/02/2020\nDescription: lit spheres\n"
)


def test_template_fields_end_the_author_list():
    assert contributors(_TEMPLATE) == "ok"  # one author, the rest are the template's fields
    two = _TEMPLATE.replace("Author: Ana Ruiz", "Authors:\n  Ana Ruiz\n  Ben Li")
    assert contributors(two) == "bare"  # two names, nothing said of who did what


@pytest.mark.parametrize(
    "header, path, named",
    [
        (_TEMPLATE, "Lab4 - Lighting.txt", True),  # the template's Assignment names its lab
        (_TEMPLATE, "shaders/Ana_Lab4_Text.txt", True),
        (_TEMPLATE, "Lab 3.txt", False),  # another lab
        (_TEMPLATE, "main.txt", False),  # a file not called after its lab
        ("Ana Ruiz\nLab 4\nPurpose: lit spheres", "Lab 4.txt", False),  # `Lab 4` alone
        ("Assignment: Lab 14", "Lab 4.txt", False),
    ],
)
def test_assignment_label_names_a_file_called_after_its_lab(header, path, named):
    assert names_file(header, path, "") is named


def test_template_header_is_complete():
    text = "/*\n" + _TEMPLATE + "*/\nvoid mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n"
    rules = {"missing-header", "incomplete-header"}
    assert [f for f in lint_source(Source("Lab4 - Lighting.txt", text)) if f.rule in rules] == []
    found = lint_source(Source("main.txt", text))
    assert [f.rule for f in found if f.rule in rules] == ["incomplete-header"]


def test_image_as_a_word_does_not_name_the_file():
    assert not names_file("renders an image of spheres", "lab/Image.glsl", "Image")


# --- how an AST rule plugs in -------------------------------------------------------------


def _fake_ast_rule() -> Rule:
    def check(ctx):
        for line in ctx.ast["pow_lines"]:
            yield Diagnostic("pow(x, 2.0) is x * x", ctx.location(line), rule="pow-two")

    module = types.ModuleType("pow_two")
    return Rule("pow-two", 1, "warning", "ast", "pow(x, 2.0).", "", check, module)


def test_ast_rule_runs_only_with_a_tree(monkeypatch):
    rules = dict(all_rules())
    rules["pow-two"] = _fake_ast_rule()
    monkeypatch.setattr(engine, "all_rules", lambda: rules)
    text = (
        "// Image.glsl: squares x\n// By Ana: all of it\n// starter framework by Daniel S. "
        "Buckstein\n"
        "float y = pow(x, 2.0); // square\n"
    )
    src = Source("Image.glsl", text)
    assert [f.rule for f in lint_source(src)] == []
    found = lint_source(src, ast={"pow_lines": [4]})
    assert [(f.rule, f.loc.line, f.penalty, f.severity) for f in found] == [
        ("pow-two", 4, 1, "warning")
    ]
    # and its findings are suppressed like any other
    src2 = Source("Image.glsl", text.replace("// square", "// square glslcheck: ignore[pow-two]"))
    assert lint_source(src2, ast={"pow_lines": [4]}) == []
