"""The program Shadertoy compiles around a tab, and the map from its lines back to the user's files.

This module owns the Shadertoy wrapper (see /work/shared/SHADERTOY.md): the prelude
(`#version 300 es`, precision lines, `HW_PERFORMANCE`, the uniform declarations), the Common tab,
the pass tab, and the `main()` footer that calls `mainImage`. It owns the uniform table
`UNIFORMS` as data, so the checker and the NumPy backend declare exactly what the GL program
declares. Every consumer of a compiled program (glslangValidator, the GL driver) reports lines of
the whole program; `Program.locate` turns such a line back into `(user path, user line)`.

Nothing here compiles or renders; it only builds text.
"""

from __future__ import annotations

import math
from bisect import bisect_right

from ..base.diagnostics import InputError
from ..base.records import record, replace
from .sources import BUFFER_TABS, Shader, Source

# A fixed iDate so renders are reproducible: 2026-01-01 00:00:00 (Shadertoy's month is 0-based).
DEFAULT_DATE: tuple[float, float, float, float] = (2026.0, 0.0, 1.0, 0.0)
DEFAULT_SIZE: tuple[int, int] = (800, 450)


@record(frozen=True)
class Uniform:
    """One Shadertoy input: `uniform <glsl_type> <name>[<array_size>];` and the value we feed it.

    `default` is what glslcheck uses when the caller gives nothing: a float/tuple for numeric
    uniforms (a tuple of tuples for `vec3[4]`), the texture unit for samplers. `iResolution`'s
    default is the default render size; renderers always set it from the real size.
    """

    name: str
    glsl_type: str
    default: object
    array_size: int | None = None
    doc: str = ""

    @property
    def declaration(self) -> str:
        suffix = f"[{self.array_size}]" if self.array_size else ""
        return f"uniform {self.glsl_type:<9} {self.name}{suffix};"

    @property
    def type_name(self) -> str:
        """The declared type as glslcheck's types print it: 'vec3', 'float[4]'."""
        return f"{self.glsl_type}[{self.array_size}]" if self.array_size else self.glsl_type


# In the order Shadertoy declares them (one line each; the line count of the prelude depends on it).
UNIFORMS: tuple[Uniform, ...] = (
    Uniform(
        "iResolution",
        "vec3",
        (float(DEFAULT_SIZE[0]), float(DEFAULT_SIZE[1]), 1.0),
        None,
        "viewport size in pixels: (width, height, 1.0)",
    ),
    Uniform("iTime", "float", 0.0, None, "seconds since the start"),
    Uniform(
        "iChannelTime",
        "float",
        (0.0, 0.0, 0.0, 0.0),
        4,
        "playback time of each input: 0 for images and buffers, "
        "as Shadertoy (shadertoy/channels.py)",
    ),
    Uniform(
        "iMouse",
        "vec4",
        (0.0, 0.0, 0.0, 0.0),
        None,
        "xy: position while the button is down, zw: where the click started (signs: SHADERTOY.md)",
    ),
    Uniform(
        "iDate", "vec4", DEFAULT_DATE, None, "(year, month 0-11, day 1-31, seconds since midnight)"
    ),
    Uniform("iSampleRate", "float", 44100.0, None, "sound sample rate"),
    Uniform(
        "iChannelResolution",
        "vec3",
        ((0.0, 0.0, 0.0),) * 4,
        4,
        "(w, h, 1) of each input, 0 when unbound",
    ),
    Uniform("iFrame", "int", 0, None, "frame number, from 0"),
    Uniform("iTimeDelta", "float", 1.0 / 60.0, None, "seconds per frame"),
    Uniform("iFrameRate", "float", 60.0, None, "frames per second"),
    Uniform("iChannel0", "sampler2D", 0, None, "input 0 (unbound: texture() returns (0,0,0,1))"),
    Uniform("iChannel1", "sampler2D", 1, None, "input 1"),
    Uniform("iChannel2", "sampler2D", 2, None, "input 2"),
    Uniform("iChannel3", "sampler2D", 3, None, "input 3"),
)
UNIFORMS_BY_NAME: dict[str, Uniform] = {u.name: u for u in UNIFORMS}


def fed_uniform(name: str, type_name: str) -> Uniform | None:
    """The Shadertoy input a plain GLSL file's `uniform <type> <name>;` receives: the one of that
    name when declared with Shadertoy's type ('vec3', 'float[4]'), else None (it then stays 0,
    on both backends). A plain file that declares `uniform vec3 iResolution;` gets the size."""
    u = UNIFORMS_BY_NAME.get(name)
    return u if u is not None and u.type_name == type_name else None


# Shadertoy compiles the Common tab on its own with only these declared.
COMMON_ONLY_UNIFORMS: tuple[str, ...] = ("iDate", "iSampleRate")

# The uniform the footer adds when supersampling (see build_program); not a Shadertoy input.
OFFSET_UNIFORM = "glslcheck_offset"
OUTPUT_NAME = "shadertoy_out_color"

_HEADER = """#version 300 es
#ifdef GL_ES
precision highp float;
precision highp int;
precision mediump sampler3D;
#endif
#define HW_PERFORMANCE 1
"""

# Passes we can wrap: the Image tab and the buffers (all call mainImage), in the order Shadertoy
# renders them (the buffers first). Sound (mainSound) and Cube A (mainCubemap) have other entry
# points and are not rendered by glslcheck. The tab names themselves: sources.TAB_NAMES and
# sources.BUFFER_TABS.
PASS_TABS = (*BUFFER_TABS, "Image")


def sample_offsets(samples: int) -> list[tuple[float, float]]:
    """The k*k regular sub-pixel offsets for `samples` = k*k, in pixels, x varying fastest
    (both backends supersample with the same grid, in the same order)."""
    k = math.isqrt(samples) if samples >= 1 else 0
    if k < 1 or k * k != samples:
        raise ValueError(f"samples must be a perfect square (1, 4, 9, 16, ...), not {samples}")
    if k == 1:
        return [(0.0, 0.0)]
    return [((i + 0.5) / k - 0.5, (j + 0.5) / k - 0.5) for j in range(k) for i in range(k)]


def as_date(date) -> tuple[float, float, float, float]:
    """iDate's value: (year, month 0-11, day 1-31, seconds since midnight) from a datetime or a
    4-tuple (taken as it is); DEFAULT_DATE for None."""
    if date is None:
        return DEFAULT_DATE
    import datetime

    if isinstance(date, datetime.datetime):
        midnight = date.replace(hour=0, minute=0, second=0, microsecond=0)
        return (
            float(date.year),
            float(date.month - 1),
            float(date.day),
            (date - midnight).total_seconds(),
        )
    year, month, day, seconds = date
    return (float(year), float(month), float(day), float(seconds))


def frame_uniforms(
    width: int,
    height: int,
    time: float = 0.0,
    frame: int = 0,
    mouse=(0.0, 0.0, 0.0, 0.0),
    date=None,
    time_delta: float = 1.0 / 60.0,
    frame_rate: float = 60.0,
) -> dict:
    """The values of one frame's Shadertoy uniforms, as every backend sets them (the others keep
    their table defaults): iResolution (width, height, 1), iTime, iFrame, iMouse, iDate
    (`as_date`), iTimeDelta, iFrameRate."""
    return {
        "iResolution": (float(width), float(height), 1.0),
        "iTime": float(time),
        "iFrame": int(frame),
        "iMouse": tuple(float(v) for v in mouse),
        "iDate": as_date(date),
        "iTimeDelta": float(time_delta),
        "iFrameRate": float(frame_rate),
    }


@record(frozen=True)
class Segment:
    """Program lines `start .. start+count-1` (1-based) are lines `first_line ..` of `path`."""

    start: int
    count: int
    path: str
    first_line: int = 1


@record(frozen=True)
class Program:
    """A whole GLSL program as handed to a compiler, with the user's lines inside it."""

    text: str
    tab: str
    segments: tuple[Segment, ...]
    samples_offset: bool = False

    @property
    def line_count(self) -> int:
        return self.text.count("\n") + (0 if self.text.endswith("\n") else 1)

    def locate(self, program_line: int) -> tuple[str, int] | None:
        """The user's (path, line) for a 1-based program line; None in the prelude or footer."""
        starts = [s.start for s in self.segments]
        i = bisect_right(starts, program_line) - 1
        if i < 0:
            return None
        seg = self.segments[i]
        if program_line >= seg.start + seg.count:
            return None
        return seg.path, seg.first_line + (program_line - seg.start)

    def program_line(self, path: str, line: int) -> int | None:
        """The inverse of `locate`: where line `line` of `path` sits in the program."""
        for seg in self.segments:
            if seg.path == path and seg.first_line <= line < seg.first_line + seg.count:
                return seg.start + (line - seg.first_line)
        return None


def _line_count(text: str) -> int:
    """Lines a text occupies once followed by a newline (a final newline adds no line)."""
    if not text:
        return 0
    return text.count("\n") + (0 if text.endswith("\n") else 1)


class _Builder:
    """Appends chunks of text and records where each user file lands."""

    def __init__(self) -> None:
        self.parts: list[str] = []
        self.next_line = 1
        self.segments: list[Segment] = []

    def add(self, text: str) -> None:
        if text and not text.endswith("\n"):
            text += "\n"
        self.parts.append(text)
        self.next_line += _line_count(text)

    def add_source(self, src: Source) -> None:
        n = _line_count(src.text)
        if n:
            self.segments.append(Segment(self.next_line, n, src.path))
        self.add(src.text)

    def program(self, tab: str, samples_offset: bool = False) -> Program:
        return Program("".join(self.parts), tab, tuple(self.segments), samples_offset)


def prelude(uniforms: tuple[Uniform, ...] = UNIFORMS, cube: frozenset[str] = frozenset()) -> str:
    """The text before the user's code: version, precision, HW_PERFORMANCE, uniforms, output.
    The iChannels named in `cube` are declared samplerCube, as Shadertoy declares a channel
    bound to a cube map (one line each still)."""
    decls = "".join(
        (replace(u, glsl_type="samplerCube") if u.name in cube else u).declaration + "\n"
        for u in uniforms
    )
    return _HEADER + decls + f"out vec4 {OUTPUT_NAME};\n"


def footer(tab: str = "Image", *, samples_offset: bool = False) -> str:
    """The `main()` Shadertoy appends. The Image pass forces alpha to 1; buffers keep it.

    With `samples_offset` a `uniform vec2 glslcheck_offset` is declared here (after the user's
    code, so user line numbers do not move) and added to fragCoord: the renderer sets it to each
    sub-pixel offset in turn when supersampling.
    """
    coord = "gl_FragCoord.xy"
    decl = ""
    if samples_offset:
        decl = f"uniform vec2 {OFFSET_UNIFORM};\n"
        coord = f"gl_FragCoord.xy + {OFFSET_UNIFORM}"
    out = "vec4(color.xyz, 1.0)" if tab == "Image" else "color"
    return (
        decl + "void main() {\n"
        f"    {OUTPUT_NAME} = vec4(1.0, 1.0, 1.0, 1.0);\n"
        "    vec4 color = vec4(1e20);\n"
        f"    mainImage(color, {coord});\n"
        f"    {OUTPUT_NAME} = {out};\n"
        "}\n"
    )


def build_program(
    shader: Shader,
    tab: str = "Image",
    *,
    samples_offset: bool = False,
    cube: frozenset[str] = frozenset(),
) -> Program:
    """The program Shadertoy compiles for `tab`: prelude, Common, the tab, footer; the
    iChannels in `cube` are samplerCube (`prelude`).

    A plain GLSL file (tab "GLSL", with its own #version and main) is returned as it is, line
    for line; `samples_offset` cannot apply to it and raises InputError. Asking for the Common
    tab gives `build_common_only(shader)`.
    """
    if tab == "Image" and "Image" not in shader.tabs and "GLSL" in shader.tabs:
        tab = "GLSL"
    if tab == "Common":
        return build_common_only(shader)
    src = shader.tabs.get(tab)
    if src is None:
        raise InputError(f"{shader.root}: error: no {tab} tab")
    if src.is_plain_glsl:
        if samples_offset:
            raise InputError(
                f"{src.path}: error: supersampling needs a Shadertoy tab (mainImage), "
                "not a plain GLSL file with its own main()"
            )
        b = _Builder()
        b.add_source(src)
        return b.program("GLSL")
    if tab not in PASS_TABS:
        raise InputError(
            f"{src.path}: error: the {tab} tab is not rendered by glslcheck "
            f"(supported: {', '.join(PASS_TABS)})"
        )
    b = _Builder()
    b.add(prelude(cube=cube))
    if shader.common is not None:
        b.add_source(shader.common)
    b.add_source(src)
    b.add(footer(tab, samples_offset=samples_offset))
    return b.program(tab, samples_offset)


def build_common_only(shader: Shader) -> Program:
    """Common compiled alone, as Shadertoy does: only iDate and iSampleRate are declared, and a
    dummy main() follows. Common code that reads iTime or iResolution fails here."""
    common = shader.common
    if common is None:
        raise InputError(f"{shader.root}: error: no Common tab")
    b = _Builder()
    b.add(prelude(tuple(UNIFORMS_BY_NAME[n] for n in COMMON_ONLY_UNIFORMS)))
    b.add_source(common)
    b.add("void main() {}\n")
    return b.program("Common")
