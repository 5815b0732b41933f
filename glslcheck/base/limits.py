"""The values a user gives a render, with one set of limits: every command and library caller
accepts and refuses exactly the same sizes, sample counts, times, frame numbers, frame counts,
rates, mouse positions, dates and frame budgets.

Each `parse_*` function turns the text of one value into the value or raises ValueError with a
readable message naming the command-line option that takes it (cli/commands/args.py wraps each
as an argparse type). `check_schedule` checks what only the values together decide (the last
frame of `--frame N --frames M` stays a valid iFrame and iTime).

The limits, and why:

- size: WIDTHxHEIGHT (or WIDTH*HEIGHT), each side 1..16384 (GL_MAX_TEXTURE_SIZE on llvmpipe), at
  most MAX_PIXELS = 4096*4096 in all: its float32 RGBA image alone is 256 MiB and verify holds two
  of them plus the comparison's arrays; 16384x16384 (4 GiB per image) ran out of memory.
- samples: a perfect square k*k from 1 to MAX_SAMPLES = 256 (16x16): each sample is a full render.
- time (iTime, --time and each of --times), mouse (iMouse): finite and at most MAX_MAGNITUDE =
  2**24 in size. The uniforms are float32 on the GPU; beyond 2**24 float32 no longer holds every
  whole number (and past 3.4e38 it holds nothing: `--time 1e39` became inf with a RuntimeWarning).
- frame (iFrame): a whole number 0..2**31-1 (iFrame is a GLSL int); `1e20` is not one.
- frames: 1..MAX_FRAMES = 1,000,000 frames (hours of rendering; frames are rendered and written
  one at a time, so memory does not grow with the count).
- fps: MIN_FPS..MAX_FPS = 0.001..1000 frames per second (iTimeDelta = 1/fps stays a normal float32).
- date (iDate): year 0..9999, month 0..11, day 1..31 (whole numbers), seconds 0 <= s < 86400.
- runs (bench): 1..1000.
- frame budget (--frame-budget, every command that renders on the NumPy backend): seconds one
  frame may render before it stops with an error at the loop it was in, MIN_FRAME_SECONDS..
  MAX_FRAME_SECONDS = 0.01..86400 (a day: a longer frame is a hang, not a render; below 10 ms
  the timer's own resolution decides). The default stays GLSLCHECK_FRAME_SECONDS, else
  base/config.py FRAME_SECONDS (300 s); the option overrides both for one command.
"""

from __future__ import annotations

import math

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Sequence

MAX_SIDE = 16384
MAX_PIXELS = 4096 * 4096
MAX_SAMPLES = 256
MAX_MAGNITUDE = float(2**24)
MAX_FRAME = 2**31 - 1
MAX_FRAMES = 1_000_000
MIN_FPS, MAX_FPS = 0.001, 1000.0
MAX_RUNS = 1000
MIN_FRAME_SECONDS, MAX_FRAME_SECONDS = 0.01, 86400.0


def check_pixels(w: int, h: int, text: str) -> None:
    """ValueError when w*h is above MAX_PIXELS."""
    if w * h > MAX_PIXELS:
        raise ValueError(
            f"a size of at most {MAX_PIXELS:,} pixels (e.g. 4096x4096), not {text!r} "
            f"({w * h:,} pixels, {w * h * 16 / 2**30:.1f} GiB per float image)"
        )


def parse_size(text: str) -> tuple[int, int]:
    """'320x180' (or '320*180') -> (320, 180); see the module docstring for the limits."""
    parts = text.lower().replace("*", "x").split("x")
    try:
        if len(parts) != 2:
            raise ValueError
        w, h = int(parts[0]), int(parts[1])
    except ValueError:
        raise ValueError(f"a size is WIDTHxHEIGHT in pixels, e.g. 320x180, not {text!r}") from None
    if not (1 <= w <= MAX_SIDE and 1 <= h <= MAX_SIDE):
        raise ValueError(f"a size must be between 1x1 and {MAX_SIDE}x{MAX_SIDE}, not {text!r}")
    check_pixels(w, h, text)
    return w, h


def whole_number(text: str, what: str) -> int:
    try:
        return int(text.strip())
    except ValueError:
        raise ValueError(f"{what} must be a whole number, not {text!r}") from None


def _show(v: float) -> str:
    return f"{v:,}" if isinstance(v, int) else f"{v:g}"


def in_range(value, low, high, what: str, text: str):
    if not low <= value <= high:
        raise ValueError(f"{what} must be from {_show(low)} to {_show(high)}, not {text!r}")
    return value


def parse_samples(text: str) -> int:
    """A perfect square from 1 to MAX_SAMPLES (the k*k sub-pixel grid both backends use)."""
    n = whole_number(text, "--samples")
    k = math.isqrt(n) if n >= 1 else 0
    if k < 1 or k * k != n or n > MAX_SAMPLES:
        raise ValueError(
            f"--samples must be a perfect square from 1 to {MAX_SAMPLES} (1, 4, 9, 16, ...), "
            f"not {text!r}"
        )
    return n


def parse_floats(
    text: str, count: int | None = None, what: str = "value", limit: float = MAX_MAGNITUDE
) -> tuple[float, ...]:
    """'0,0.5,1' -> (0.0, 0.5, 1.0): finite numbers of size at most `limit`; exactly `count` if
    given."""
    items = [t.strip() for t in text.split(",")]
    try:
        values = tuple(float(t) for t in items)
    except ValueError:
        raise ValueError(f"{what} must be comma-separated numbers, not {text!r}") from None
    if count is not None and len(values) != count:
        raise ValueError(
            f"{what} needs {count} comma-separated number{'s' if count != 1 else ''}, not {text!r}"
        )
    if not all(math.isfinite(v) and abs(v) <= limit for v in values):
        kind = "a finite number" if count == 1 else "finite numbers"
        raise ValueError(f"{what} must be {kind} from -{limit:.10g} to {limit:.10g}, not {text!r}")
    return values


def parse_time(text: str) -> float:
    """iTime in seconds: finite, |T| <= MAX_MAGNITUDE."""
    return parse_floats(text, 1, "--time")[0]


def parse_times(text: str) -> tuple[float, ...]:
    """'0,0.5,1': one frame per time, each as --time."""
    return parse_floats(text, None, "--times")


def parse_mouse(text: str) -> tuple[float, float, float, float]:
    """'X,Y,Z,W' -> iMouse (pixels; signs of Z and W as on Shadertoy)."""
    x, y, z, w = parse_floats(text, 4, "--mouse")
    return x, y, z, w


def parse_frame(text: str) -> int:
    """iFrame: a whole number from 0 to MAX_FRAME."""
    return in_range(whole_number(text, "--frame"), 0, MAX_FRAME, "--frame", text)


def parse_frames(text: str) -> int:
    """A frame count from 1 to MAX_FRAMES."""
    return in_range(whole_number(text, "--frames"), 1, MAX_FRAMES, "--frames", text)


def parse_fps(text: str) -> float:
    return in_range(parse_floats(text, 1, "--fps")[0], MIN_FPS, MAX_FPS, "--fps", text)


def parse_runs(text: str) -> int:
    return in_range(whole_number(text, "--runs"), 1, MAX_RUNS, "--runs", text)


def parse_frame_budget(text: str) -> float:
    """Seconds one frame may render on the CPU: MIN_FRAME_SECONDS..MAX_FRAME_SECONDS."""
    seconds = parse_floats(text, 1, "--frame-budget", limit=MAX_FRAME_SECONDS)[0]
    return in_range(seconds, MIN_FRAME_SECONDS, MAX_FRAME_SECONDS, "--frame-budget", text)


def parse_date(text: str) -> tuple[float, float, float, float]:
    """'Y,M,D,S' -> iDate: year 0..9999, month 0..11, day 1..31, seconds since midnight."""
    year, month, day, seconds = parse_floats(text, 4, "--date")
    for value, low, high, what in (
        (year, 0, 9999, "year"),
        (month, 0, 11, "month (0 = January)"),
        (day, 1, 31, "day"),
    ):
        if value != int(value) or not low <= value <= high:
            raise ValueError(
                f"--date: the {what} must be a whole number from {low} to {high}, not {text!r}"
            )
    if not 0 <= seconds < 86400:
        raise ValueError(
            f"--date: the seconds since midnight must be from 0 to below 86400, not {text!r}"
        )
    return year, month, day, seconds


def check_schedule(
    frame: int = 0,
    frames: int | None = None,
    fps: float = 60.0,
    time: float | None = None,
    times: Sequence[float] | None = None,
) -> None:
    """ValueError when the last frame of a run is not a valid iFrame or iTime."""
    if frames is None:
        return
    last = frame + frames - 1
    if last > MAX_FRAME:
        raise ValueError(f"--frame {frame} with --frames {frames} runs past iFrame {MAX_FRAME}")
    end = (time or 0.0) + (frames - 1) / fps
    if abs(end) > MAX_MAGNITUDE or abs(last / fps) > MAX_MAGNITUDE:
        raise ValueError(
            f"--frames {frames} at --fps {fps:g} runs iTime past {MAX_MAGNITUDE:.10g} seconds"
        )
