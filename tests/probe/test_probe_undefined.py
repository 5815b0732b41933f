"""probe shows the step where an undefined value enters (tests/verify/undefined marks the
reads with `// undefined: KIND`)."""

from __future__ import annotations

from pathlib import Path

from glslcheck.verification.probe import Inputs, Probe, format_pixel

CASES = Path(__file__).resolve().parents[1] / "verify" / "undefined"


def _marked(path: Path) -> list[tuple[int, str]]:
    lines = path.read_text().splitlines()
    return [
        (n, line.split("// undefined:")[1].split()[0])
        for n, line in enumerate(lines, 1)
        if "// undefined:" in line
    ]


def test_out_parameter_enters_at_the_call_before_its_read():
    path = CASES / "outparam.glsl"
    inputs = Inputs(size=(32, 18))
    report = Probe(path).pixel(3, 9, inputs)
    kinds = [s.kind for s in report.steps]
    entry = kinds.index("undefined")
    ((line, kind),) = _marked(path)
    step = report.steps[entry]
    assert step.why == kind == "out-parameter" and step.read_line == line
    # the read comes after the entry, in the callee
    assert any(s.line == line for s in report.steps[entry + 1 :])
    text = format_pixel(report, str(path), inputs)
    assert "UNDEFINED in the shader" in text and f"(read at line {line})" in text
    assert report.steps[entry].to_json()["undefined"] == "out-parameter"


def test_uninitialized_local_enters_at_its_declaration():
    path = CASES / "local.glsl"
    report = Probe(path).pixel(3, 9, Inputs(size=(32, 18)))
    steps = [s for s in report.steps if s.kind == "undefined"]
    ((line, kind),) = _marked(path)
    assert [(s.why, s.read_line) for s in steps] == [(kind, line)]
    assert steps[0].line < line  # the declaration, before the read


def test_a_constant_operation_enters_where_it_is():
    path = CASES / "divzero.glsl"
    report = Probe(path).pixel(3, 9, Inputs(size=(32, 18)))
    assert [(s.line, s.why) for s in report.steps if s.kind == "undefined"] == _marked(path)


def test_nan_pixels_that_depend_on_an_undefined_value_are_named():
    """The square root's argument is an out parameter read before it is written: WebGL's zero
    makes it negative (NaN) in every pixel; other values would not."""
    path = CASES / "nan_from_out_parameter.glsl"
    inputs = Inputs(size=(16, 9))
    report = Probe(path).nan_origins(inputs)
    (origin,) = report.origins
    assert origin.pixels == report.nan_pixels > 0
    assert origin.undefined_pixels == origin.pixels
    ((line, kind),) = _marked(path)
    assert [(u["line"], u["kind"]) for u in report.undefined_reads] == [(line, kind)]


def test_nan_pixels_of_a_program_without_undefined_reads_stay_the_operations():
    report = Probe(CASES.parents[1] / "probe" / "shaders" / "light_in_plane").nan_origins(
        Inputs(size=(80, 45))
    )
    assert report.undefined_reads == [] and all(o.undefined_pixels == 0 for o in report.origins)


def test_uninitialized_global_enters_at_the_start_of_mainimage():
    path = CASES / "global.glsl"
    inputs = Inputs(size=(32, 18))
    report = Probe(path).pixel(3, 9, inputs)
    ((line, kind),) = _marked(path)
    first = report.steps[0]  # before mainImage's first statement
    assert (first.kind, first.why, first.read_line) == ("undefined", kind, line)
    assert first.name == "edge" and first.line < line  # at the global's declaration
    assert [s for s in report.steps if s.kind == "undefined"] == [first]
    text = format_pixel(report, str(path), inputs)
    assert "a global declared without an initializer" in text and f"(read at line {line})" in text
