"""glslcheck and glslangValidator agree on accept/reject.

* every valid shader (tests/corpus/, lab_shaders/*/) is accepted by both;
* a sample of programmatic mutations of them (tools/mutation_agreement.py) is judged alike;
* the cases where glslcheck deliberately differs from glslangValidator are listed in
  `KNOWN_DIFFERENCES`, each with the reason; each is checked here, so the list stays true.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

from glslcheck.base.diagnostics import register_source
from glslcheck.semantics.agreement import glslang_errors, our_errors
from glslcheck.shadertoy.sources import Shader, Source, find_shaders

ROOT = Path(__file__).resolve().parents[2]
VALID = sorted(
    p for p in (ROOT / "tests" / "corpus").glob("*") if not p.name.startswith(".")
) + sorted(p for p in (ROOT / "lab_shaders").glob("*/") if p.is_dir())


def _load_tool():
    spec = importlib.util.spec_from_file_location(
        "mutation_agreement", ROOT / "tools" / "mutation_agreement.py"
    )
    mod = importlib.util.module_from_spec(spec)
    sys.modules["mutation_agreement"] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.parametrize("path", VALID, ids=lambda p: p.name)
def test_valid_shaders_accepted_by_both(path, glslang):
    for shader in find_shaders([str(path)]):
        assert [d.message for d in our_errors(shader)] == []
        assert glslang_errors(shader) == []


MAIN = (
    "\nvoid mainImage(out vec4 fragColor, in vec2 fragCoord)\n{\n    fragColor = vec4(g(1.0));\n}\n"
)

# Names a field selection (after '.') takes that also name a struct: a member's name lives in its
# struct's own name space, so `t.L` selects member L even where L is a type.
FIELDS_NAMED_LIKE_TYPES = [
    "struct S { float v; };\nstruct L { S L[2]; float n; };\n"
    "float g(float x) { L t; t.L[0] = S(x); t.n = 2.0; return t.L[0].v + t.n; }\n",
    "struct P { float P; };\nfloat g(float x) { P p = P(x); p.P += 1.0; return p.P; }\n",
    "struct A { float b; };\nstruct B { A A; };\n"
    "float g(float x) { B q = B(A(x)); return q.A.b; }\n",
]


@pytest.mark.parametrize("text", FIELDS_NAMED_LIKE_TYPES)
def test_fields_named_like_types_are_accepted_by_both(text, glslang):
    shader = Shader(root="fields")
    register_source("Image.glsl", text + MAIN)
    shader.tabs["Image"] = Source("Image.glsl", text + MAIN, "Image")
    assert [d.message for d in our_errors(shader)] == []
    assert glslang_errors(shader) == []


# Programs where glslangValidator (as glslcheck.semantics.glslang runs it: compile only, no -l)
# accepts what a GL driver rejects. Each: (name, Image tab text, why glslang is wrong here).
KNOWN_DIFFERENCES = [
    (
        "call-without-definition",
        "float g(float x);\n" + MAIN,
        "glslangValidator without -l does not link; the driver (and glslangValidator -l) rejects "
        "a call to a function that has no body at link time",
    ),
    (
        "static-recursion",
        "float g(float x) { return x > 0.0 ? g(x - 1.0) : 0.0; }\n" + MAIN,
        "GLSL ES 3.00 section 6.1 forbids recursion; glslang detects it only when linking (-l)",
    ),
    (
        "case-label-type",
        "float g(float x)\n{\n    switch (int(x))\n    {\n    case 1u:\n        return 1.0;\n    "
        "}\n"
        "    return 0.0;\n}\n" + MAIN,
        "GLSL ES 3.00 section 6.2: the case labels' type must match the switch value's; "
        "glslang does not check",
    ),
]


@pytest.mark.parametrize("name,text,why", KNOWN_DIFFERENCES, ids=[k[0] for k in KNOWN_DIFFERENCES])
def test_known_differences(name, text, why, glslang):
    shader = Shader(root=name)
    register_source("Image.glsl", text)
    shader.tabs["Image"] = Source("Image.glsl", text, "Image")
    assert our_errors(shader), f"{name}: glslcheck should reject ({why})"
    assert glslang_errors(shader) == [], (
        f"{name}: glslangValidator now rejects it; move it to tests/check/invalid/"
    )
    if "-l" in why:
        # Demonstrate that the reference compiler itself rejects it once it links.
        import os
        import tempfile

        from glslcheck.shadertoy.wrapper import build_program

        fd, path = tempfile.mkstemp(suffix=".frag")
        with os.fdopen(fd, "w") as f:
            f.write(build_program(shader).text)
        try:
            proc = subprocess.run([glslang, "-l", path], capture_output=True, text=True)
        finally:
            os.unlink(path)
        assert proc.returncode != 0, f"{name}: glslangValidator -l accepts it"


def test_mutation_sample_agrees(glslang):
    tool = _load_tool()
    report = tool.run(limit=60, seed=7)
    assert report.total >= 50
    bad = [d for d in report.disagreements if not d.explained]
    assert not bad, "\n".join(d.describe() for d in bad)
