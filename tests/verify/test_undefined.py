"""verify names the shader's undefined behaviour instead of counting it as a mismatch.

The shaders in undefined/ mark their undefined reads (`// undefined: KIND`): a ray tracer whose
`rand(out float seed)` reads the seed before writing it and draws in a `while (true)` loop until
a point falls inside the unit sphere (the loop ends at llvmpipe's loop limit, which verify
emulates, or at once when the seed varies), and one small case per kind.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from glslcheck.backends.numpy_engine.program import compile_numpy
from glslcheck.cli.main import main
from glslcheck.shadertoy.sources import load_shader
from glslcheck.verification.compare import JSON_KEYS, compare, depends_on_undefined
from glslcheck.verification.verify import JSON_KEYS as VERIFY_KEYS
from glslcheck.verification.verify import verify_frames

CASES = Path(__file__).resolve().parent / "undefined"
SHADERS = sorted(p.name for p in CASES.glob("*.glsl"))
SIZE = (32, 18)


def _marked_lines(path: Path) -> set[int]:
    lines = path.read_text().splitlines()
    return {n for n, line in enumerate(lines, 1) if "// undefined:" in line}


def test_compare_sets_undefined_pixels_apart():
    a = np.zeros((10, 20, 3), np.float32)
    b = a.copy()
    b[2:8, 3:9] = 0.5  # 36 pixels differ
    differ = np.abs(a - b).max(axis=-1) > 0
    plain = compare(a, b)
    assert plain.verdict == "mismatch" and plain.mismatched_pixels == int(differ.sum())
    whole = compare(a, b, undefined=differ)
    assert whole.verdict == "undefined" and not whole.match
    assert whole.undefined_pixels == int(differ.sum()) and whole.mismatched_pixels == 0
    assert whole.worst[0].kind == "undefined"
    half = differ.copy()
    half[:, :6] = False  # the pixels left of x = 6 stay unexplained: still a mismatch
    part = compare(a, b, undefined=half)
    assert part.verdict == "mismatch"
    assert part.mismatched_pixels == int((differ & ~half).sum())
    assert part.undefined_pixels == int((differ & half).sum())
    assert list(whole.to_json()) == list(JSON_KEYS)
    assert whole.to_json()["verdict"] == "undefined"


def test_depends_on_undefined_counts_display_and_nan_differences():
    a = np.zeros((2, 2, 4), np.float32)
    b = a.copy()
    b[0, 0, 0] = 1.0 / 255.0  # within the tolerance
    b[0, 1, 1] = 0.5
    b[1, 0, 2] = np.nan
    b[1, 1, 3] = 7.0  # alpha is not compared
    assert depends_on_undefined(a, b).tolist() == [[False, True], [True, False]]


def test_vary_module_draws_where_the_checker_found_reads():
    shader = load_shader(CASES / "raytracer_out_seed.glsl")
    zero, vary = compile_numpy(shader), compile_numpy(shader, undefined="vary")
    assert "X.undefined" not in zero.source
    assert vary.source.count("X.undefined(") == 1  # rand's seed, on entry


def test_a_driver_with_other_undefined_values_gets_verdict_undefined():
    """The GL side here is a driver whose undefined values are not zeros (the NumPy module that
    draws them anew): the ray tracer's sphere pixels then end their loop at once instead of at
    the loop limit, and every pixel that differs must be named undefined, at rand's read."""
    path = CASES / "raytracer_out_seed.glsl"
    shader = load_shader(path)
    driver = compile_numpy(shader, undefined="vary")
    (result,) = verify_frames(shader, size=SIZE, programs=[compile_numpy(shader), driver])
    c = result.comparison
    assert c.verdict == "undefined", c.summary()
    assert c.mismatched_pixels == 0 and c.undefined_pixels > 0
    assert [(u["line"], u["kind"]) for u in c.undefined_lines] == [
        (min(_marked_lines(path)), "out-parameter")
    ]
    assert c.undefined_lines[0]["pixels"] == c.undefined_pixels


@pytest.mark.parametrize("name", SHADERS)
def test_live_driver_differs_only_where_undefined(gl, name):
    """Against llvmpipe, whatever values it gives the undefined reads: no pixel is a mismatch,
    and every undefined pixel is traced to a marked line."""
    path = CASES / name
    (result,) = verify_frames(path, size=SIZE)
    c = result.comparison
    assert c.verdict in ("match", "undefined"), c.summary()
    assert c.mismatched_pixels == 0 and c.nan_mismatched_pixels == 0
    if c.undefined_pixels:
        assert c.undefined_lines
        assert {u["line"] for u in c.undefined_lines} <= _marked_lines(path)


def test_cli_text_and_json(gl, capsys, tmp_path):
    path = CASES / "local.glsl"
    code = main(["verify", str(path), "--size", "32x18", "--format", "json"])
    out = json.loads(capsys.readouterr().out)
    assert list(out) == list(VERIFY_KEYS)
    if out["verdict"] == "match":  # this driver zero-initialises locals too
        assert code == 0
        pytest.skip("this driver gives the uninitialized local WebGL's value: nothing differs")
    assert code == 1 and out["verdict"] == "undefined" and out["mismatched_pixels"] == 0
    assert out["undefined_lines"][0]["kind"] == "uninitialized-local"
    assert main(["verify", str(path), "--size", "32x18"]) == 1
    text = capsys.readouterr().out
    assert "UNDEFINED IN THE SHADER" in text and "MISMATCH" not in text
    line = out["undefined_lines"][0]["line"]
    assert f"{path}:{line}:" in text


def test_report_page_names_undefined_pixels(gl):
    from glslcheck.verification.report import gather, page_html

    shader = load_shader(CASES / "local.glsl")
    report = gather(shader, size=SIZE, backends=("numpy", "gl"), bench=None)
    ((a, b, c, _),) = report.pairs
    assert c.verdict in ("match", "undefined") and c.mismatched_pixels == 0
    page = page_html([report], SIZE, 0.0, "report")
    assert ("undefined in the shader" in page) == (c.verdict == "undefined")


def test_vary_module_draws_a_global_in_init_globals():
    shader = load_shader(CASES / "global.glsl")
    zero, vary = compile_numpy(shader), compile_numpy(shader, undefined="vary")
    assert "X.undefined" not in zero.source
    init = vary.source[vary.source.index("def init_globals") :]
    assert vary.source.count("X.undefined(") == init.count("X.undefined(") == 1


def test_a_global_set_on_some_paths_is_undefined_against_llvmpipe(llvmpipe):
    """A global set to a constant inside a march loop on some paths only and read on every
    pixel: llvmpipe folds it to that constant on the other paths, WebGL and the NumPy backend
    read zero there. Every differing pixel must be named undefined, at the read, and none
    counted as a mismatch; the pixels where the loop sets it are alike on both sides."""
    path = CASES / "global.glsl"
    (result,) = verify_frames(path, size=SIZE)
    c = result.comparison
    assert c.verdict == "undefined", c.summary()
    assert c.mismatched_pixels == 0 and c.nan_mismatched_pixels == 0
    assert 0 < c.undefined_pixels < SIZE[0] * SIZE[1]
    assert [(u["line"], u["kind"], u["pixels"]) for u in c.undefined_lines] == [
        (min(_marked_lines(path)), "uninitialized-global", c.undefined_pixels)
    ]


def test_globals_assigned_before_their_reads_match_llvmpipe(llvmpipe, capsys):
    path = CASES / "global_assigned.glsl"
    (result,) = verify_frames(path, size=SIZE)
    c = result.comparison
    assert c.verdict == "match" and c.undefined_pixels == 0, c.summary()
    assert main(["check", str(path)]) == 0
    assert "warning" not in capsys.readouterr().err


def test_cli_names_the_global_in_text_and_json(llvmpipe, capsys):
    path = CASES / "global.glsl"
    assert main(["verify", str(path), "--size", "32x18", "--format", "json"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert out["verdict"] == "undefined" and out["mismatched_pixels"] == 0
    (read,) = out["undefined_lines"]
    assert read["kind"] == "uninitialized-global" and read["pixels"] == out["undefined_pixels"]
    assert main(["verify", str(path), "--size", "32x18"]) == 1
    text = capsys.readouterr().out
    assert "UNDEFINED IN THE SHADER" in text and "MISMATCH" not in text
    assert f"{path}:{read['line']}:{read['column']}" in text
    assert "a global read before it is assigned" in text


def test_every_kind_has_words_in_verify_and_probe():
    from glslcheck.cli.commands.verify import UNDEFINED_KINDS
    from glslcheck.semantics.analysis.undefined import KINDS
    from glslcheck.verification.probe import UNDEFINED_ENTRIES

    assert set(UNDEFINED_KINDS) == set(UNDEFINED_ENTRIES) == set(KINDS)
