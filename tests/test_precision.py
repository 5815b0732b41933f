"""One list of the NumPy backend's float precisions (glslcheck/base/precision.py): the CLI's
`--precision` choices, bench's configurations, the API, verify and the runtime accept exactly
those, and refuse the others with the same message."""

from __future__ import annotations

import pytest

from glslcheck.backends import registry as api
from glslcheck.backends.numpy_engine.runtime import Runtime
from glslcheck.base.precision import PRECISIONS
from glslcheck.cli.main import build_parser
from glslcheck.verification.bench import configurations
from glslcheck.verification.verify import verify_frames

SHADER = "void mainImage(out vec4 o, in vec2 f) { o = vec4(f / iResolution.xy, 0.1, 1.0); }"
REFUSED = ("float128", "mediump", "highp", "")


@pytest.mark.parametrize("command", ["render", "verify"])
def test_the_cli_offers_the_list(command):
    parser = build_parser(command)
    sub = next(a for a in parser._actions if a.dest == "command").choices[command]
    (action,) = [a for a in sub._actions if "--precision" in a.option_strings]
    assert tuple(action.choices) == PRECISIONS and action.default in PRECISIONS


def test_bench_measures_the_list():
    assert (
        tuple(dict.fromkeys(c.precision for c in configurations() if c.backend == api.DEFAULT))
        == PRECISIONS
    )


def test_the_runtime_and_the_api_take_the_list_and_refuse_the_rest(make_shader):
    for p in PRECISIONS:
        assert Runtime(p).F.__name__ == p
    prog = api.compile(make_shader(SHADER), backend="numpy")
    for p in PRECISIONS:
        assert prog.render(size=(4, 2), precision=p).shape == (2, 4, 4)
    for p in REFUSED:
        message = f"precision must be one of {', '.join(PRECISIONS)}, not {p!r}"
        with pytest.raises(ValueError) as runtime_error:
            Runtime(p)
        with pytest.raises(ValueError) as api_error:
            prog.render(size=(4, 2), precision=p)
        with pytest.raises(ValueError) as verify_error:  # refused before anything is compiled
            next(iter(verify_frames(make_shader(SHADER), precision=p)))
        assert (
            str(runtime_error.value) == str(api_error.value) == str(verify_error.value) == message
        )
