"""Every command accepts and refuses the same values of the options they share (one
module of limits, glslcheck/base/limits.py), and hostile values (huge counts, sizes and
times) are usage errors (exit 2 with a message), not warnings, tracebacks or hours of work."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from glslcheck.base import limits
from glslcheck.cli.main import build_parser, main

RENDERING = (
    "render",
    "verify",
    "bench",
    "report",
    "probe",
)  # every command that renders on the CPU

GOOD = {
    "--size": ["320x180", "320X180", "320*180", "1x1", "16384x1", "4096x4096"],
    "--samples": ["1", "4", "9", "256"],
    "--time": ["0", "-1.5", "1e3", "16777216"],
    "--times": ["0,0.5,1", "16777216"],
    "--frame": ["0", "7", str(2**31 - 1)],
    "--frames": ["1", "30", "1000000"],
    "--fps": ["60", "0.001", "1000", "29.97"],
    "--mouse": ["0,0,0,0", "10,20,-10,-20"],
    "--date": ["2026,0,1,0", "1999,11,31,86399.5"],
    "--precision": ["float16", "float32", "float64"],
    "--runs": ["1", "1000"],
    "--frame-budget": ["0.01", "1", "2.5", "300", "86400", "1e3"],
}
BAD = {
    "--size": ["320", "0x10", "16385x1", "4097x4096", "axb", "320x180x2", ""],
    "--samples": ["0", "2", "400", "289", "1.0", "x", "-4"],
    "--time": ["1e39", "inf", "nan", "-1e39", "16777217", "1,2", "x"],
    "--times": ["0,1e39", "0,,1", "nan"],
    "--frame": ["1e20", "-1", "1.5", str(2**31), "x"],
    "--frames": ["0", "-3", "100000000", "1e3", "x"],
    "--fps": ["0", "-60", "inf", "nan", "1e-9", "1e6"],
    "--mouse": ["1,2,3", "1,2,3,4,5", "nan,0,0,0", "1e39,0,0,0"],
    "--date": [
        "2026,12,1,0",
        "2026,0,0,0",
        "2026,0,1,86400",
        "2026.5,0,1,0",
        "2026,0,1",
        "1e39,0,1,0",
    ],
    "--precision": ["float128", "mediump"],
    "--runs": ["0", "1001", "2.5"],
    "--frame-budget": ["0", "-1", "0.001", "86401", "1e39", "inf", "nan", "1,2", "x", ""],
}


def _options(command: str) -> set[str]:
    parser = build_parser(command)
    sub = next(a for a in parser._actions if a.dest == "command")
    return {s for action in sub.choices[command]._actions for s in action.option_strings}


def _parse(command: str, option: str, value: str) -> int:
    """0 when the parser takes the value, else the usage error's exit code."""
    extra = ["--frames", "2", "-o", "a.gif"] if command == "render" and option == "--fps" else []
    extra += (
        ["--nan"] if command == "probe" else []
    )  # probe needs one of --pixel, --frag-coord, --nan
    argv = [command, "shader.glsl", *extra, f"{option}={value}"]
    try:
        build_parser(command).parse_args(argv)
    except SystemExit as e:
        return int(e.code or 0)
    return 0


CASES = [(c, o) for c in RENDERING for o in GOOD if o in _options(c)]


def test_the_shared_options_are_on_every_rendering_command():
    for option in (
        "--size",
        "--samples",
        "--time",
        "--frame",
        "--frames",
        "--fps",
        "--mouse",
        "--date",
        "--precision",
    ):
        assert option in _options("render") and option in _options("verify"), option
    assert {"--size", "--time", "--runs"} <= _options("bench")
    for command in RENDERING:
        assert "--frame-budget" in _options(command), command


@pytest.mark.parametrize("command,option", CASES)
def test_every_command_accepts_the_same_values(command, option):
    for value in GOOD[option]:
        assert _parse(command, option, value) == 0, (command, option, value)


@pytest.mark.parametrize("command,option", CASES)
def test_every_command_refuses_the_same_values(command, option, capsys):
    for value in BAD[option]:
        assert _parse(command, option, value) == 2, (command, option, value)
        err = capsys.readouterr().err
        assert "error:" in err and "Traceback" not in err and "Warning" not in err


def test_the_parsers_agree_with_their_documented_limits():
    assert limits.parse_size("4096x4096") == (4096, 4096)
    assert limits.parse_samples(str(limits.MAX_SAMPLES)) == limits.MAX_SAMPLES
    assert limits.parse_time(str(limits.MAX_MAGNITUDE)) == limits.MAX_MAGNITUDE
    assert limits.parse_frame(str(limits.MAX_FRAME)) == limits.MAX_FRAME
    assert limits.parse_frames(str(limits.MAX_FRAMES)) == limits.MAX_FRAMES
    with pytest.raises(ValueError, match="--frames"):
        limits.parse_frames(str(limits.MAX_FRAMES + 1))
    assert limits.parse_frame_budget(str(limits.MIN_FRAME_SECONDS)) == limits.MIN_FRAME_SECONDS
    assert limits.parse_frame_budget(str(limits.MAX_FRAME_SECONDS)) == limits.MAX_FRAME_SECONDS
    with pytest.raises(ValueError, match="--frame-budget must be from 0.01 to 86400"):
        limits.parse_frame_budget("0")


RUNAWAY = (
    "void mainImage(out vec4 c, in vec2 p) {\n    float x = 0.0;\n"
    "    for (int i = 0; i < 99999; i++) { for (int j = 0; j < 99999; j++) { x += 1.0; } }\n"
    "    c = vec4(x);\n}\n"
)


@pytest.mark.parametrize("command,options", [("render", ["-o", "a.npy"]), ("probe", ["--nan"])])
def test_frame_budget_stops_the_frame_and_leaves_the_environment_as_it_was(
    command, options, tmp_path, capsys, monkeypatch
):
    """--frame-budget overrides GLSLCHECK_FRAME_SECONDS (here 30 s, so that without the option
    the test fails rather than hangs) for one command: the runaway loops stop at 0.2 s with the
    error at the inner loop, and the variable is as it was after main() returns (main may run
    again in the same process)."""
    monkeypatch.setenv("GLSLCHECK_FRAME_SECONDS", "30")
    shader = tmp_path / "Image.glsl"
    shader.write_text(RUNAWAY)
    argv = [str(tmp_path / o) if o.endswith(".npy") else o for o in options]
    code = main([command, str(shader), *argv, "--size", "8x8", "--frame-budget", "0.2"])
    err = capsys.readouterr().err
    assert code == 1, err
    assert f"{shader}:3:39: error: the frame was still rendering after 0.2 s" in err, err
    assert "--frame-budget SECONDS" in err  # the help names the option
    assert os.environ["GLSLCHECK_FRAME_SECONDS"] == "30"
    monkeypatch.delenv("GLSLCHECK_FRAME_SECONDS")
    main([command, str(shader), *argv, "--size", "8x8", "--frame-budget", "0.2"])
    assert "GLSLCHECK_FRAME_SECONDS" not in os.environ


@pytest.mark.parametrize("command", ["render", "verify"])
def test_a_schedule_past_the_last_iframe_is_a_usage_error(command, tmp_path, capsys):
    shader = tmp_path / "Image.glsl"
    shader.write_text("void mainImage(out vec4 c, in vec2 p) { c = vec4(1.0); }\n")
    out = ["-o", str(tmp_path / "a.gif")] if command == "render" else []
    code = main(
        [command, str(shader), *out, "--frame", str(limits.MAX_FRAME - 5), "--frames", "10"]
    )
    assert code == 2
    assert "runs past iFrame" in capsys.readouterr().err


def test_time_1e39_is_a_usage_error_not_a_runtime_warning(tmp_path):
    shader = tmp_path / "Image.glsl"
    shader.write_text("void mainImage(out vec4 c, in vec2 p) { c = vec4(iTime); }\n")
    proc = subprocess.run(
        [
            sys.executable,
            "-W",
            "error",
            "-m",
            "glslcheck",
            "render",
            str(shader),
            "-o",
            str(tmp_path / "a.png"),
            "--time",
            "1e39",
        ],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2
    assert (
        "--time" in proc.stderr
        and "RuntimeWarning" not in proc.stderr
        and "Traceback" not in proc.stderr
    )
    assert not (tmp_path / "a.png").exists()


def test_a_long_schedule_is_not_built_first():
    """`verify --frames 100000000` built its whole frame list before the first frame."""
    from glslcheck.verification.verify import frame_specs

    specs = frame_specs(frames=10**8, fps=30.0, frame=5)
    assert len(specs) == 10**8 and sys.getsizeof(specs) < 1000
    assert (specs[0].frame, specs[-1].frame) == (5, 10**8 + 4)
    assert specs[3].time == 8 / 30.0 and specs[3].time_delta == 1 / 30.0
    assert [s.frame for s in specs[:3]] == [5, 6, 7]


def test_frame_budget_stops_a_probe_trace(tmp_path):
    """`probe --pixel` traced a runaway loop with no budget at all (10**10 iterations: hours);
    now the trace stops as a frame does. A subprocess with a timeout, so the old behaviour fails
    the test instead of hanging it."""
    shader = tmp_path / "Image.glsl"
    shader.write_text(RUNAWAY)
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "glslcheck",
            "probe",
            str(shader),
            "--pixel",
            "0,0",
            "--size",
            "8x8",
            "--frame-budget",
            "0.5",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 1, proc.stderr
    assert f"{shader}:3:39: error: the frame was still rendering after 0.5 s" in proc.stderr, (
        proc.stderr
    )
