"""Compiling a Shadertoy shader with WebGL 2 (ANGLE) and rendering it as Shadertoy's page does.

`compile_webgl(shader)` builds the exact program Shadertoy compiles (`glslcheck.shadertoy.wrapper.
build_program`: prelude, Common, the tab, the footer that forces alpha to 1 in the Image pass),
hands it to the browser's WebGL2 context with Shadertoy's vertex stage (one triangle over the
viewport from a vertex buffer at attribute 0), and turns ANGLE's error log into `GlslError`
diagnostics located in the user's files, as `gl_backend` does with Mesa's log (the same
`Program.locate` map). `WebGLProgram.render(...)` takes the arguments of `GLProgram.render` and
gives the same float32 (height, width, 4) image, top row first: drawn into an RGBA32F texture
(EXT_color_buffer_float) and read back with `readPixels(FLOAT)`, neither clamped nor quantised.

Uniforms are set as Shadertoy's page sets them (glslcheck/shadertoy/wrapper.py `UNIFORMS`:
iResolution, iTime, iMouse, iChannelTime, iDate, iChannelResolution, iSampleRate, iChannel0..3 =
units 0..3, iFrame, iTimeDelta, iFrameRate); inactive ones are skipped by WebGL.
`render(channels=...)` binds the channels (glslcheck.shadertoy.channels.ChannelInput) as RGBA32F
textures on units 0..3, with their filter, wrap and glslcheck's mipmap levels, as the GL backend
does; without it they are unbound.

What SwiftShader's WebGL does with them (measured, tests/webgl/test_channels_webgl.py): it
ignores lowp, so lookups return the exact float32 filtered value where llvmpipe (and the NumPy
backend) truncate to 10 mantissa bits; nearest and linear lookups and explicit-LOD mipmap
lookups are otherwise equal to NumPy's to float32 rounding. Its implicit LOD, projective lookups
and per-pixel-LOD textureLodOffset differ from llvmpipe's: driver-dependent pixels.
Supersampling uses the `glslcheck_offset` program variant and the sub-pixel grid of the GL
backend (`shadertoy.wrapper.sample_offsets`), summed in float64 and rounded to float32 once.

`webgl_diagnostics(shader, tab)` is ANGLE's verdict for `check --webgl`: the errors of compiling
and linking the program Shadertoy compiles for `tab` ("Common" = Common alone), in the user's
files; an empty list when ANGLE accepts it.
"""

from __future__ import annotations

import base64
import re
import weakref
from dataclasses import dataclass, field

import numpy as np

from ...base.diagnostics import Diagnostic, GlslError, Location, source_line
from ...base.records import replace
from ...shadertoy.frame_inputs import FrameInputs, frame_inputs
from ...shadertoy.sources import Shader
from ...shadertoy.wrapper import OFFSET_UNIFORM, UNIFORMS, Program, build_program, frame_uniforms
from ..driver_log import driver_diagnostics, entry_location, parse_driver_log
from .browser import Browser, WebGLTimeout, get_browser

RULE = "webgl-compile"

# Shadertoy's vertex stage for WebGL 2: its header's first lines, then `pos` at location 0.
VERTEX_SHADER = """#version 300 es
#ifdef GL_ES
precision highp float;
precision highp int;
precision mediump sampler3D;
#endif
layout(location = 0) in vec2 pos; void main() { gl_Position = vec4(pos.xy,0.0,1.0); }
"""

# How each GLSL type of the uniform table is set (harness.js `setUniform`).
_KINDS = {"float": "1f", "vec2": "2f", "vec3": "3f", "vec4": "4f", "int": "1i", "sampler2D": "1i"}


def _flatten(value) -> list[float]:
    if isinstance(value, (tuple, list)):
        return [x for v in value for x in _flatten(v)]
    return [value]


def uniform_values(
    width: int,
    height: int,
    time: float,
    frame: int,
    mouse,
    date,
    time_delta: float,
    frame_rate: float,
    channels=None,
) -> list[list]:
    """[[name, kind, values], ...] for every Shadertoy uniform, in the table's order;
    `channels` (iChannel0..3, see `WebGLProgram.render`) set iChannelResolution."""
    given = frame_uniforms(width, height, time, frame, mouse, date, time_delta, frame_rate)
    if channels is not None:
        from ...shadertoy.channels import channel_uniforms

        given["iChannelResolution"] = channel_uniforms(channels)["iChannelResolution"]
    out = []
    for u in UNIFORMS:
        kind = _KINDS[u.glsl_type] + ("v" if u.array_size else "")
        out.append([u.name, kind, _flatten(given.get(u.name, u.default))])
    return out


# Bytes of base64 text per call into the page: one DevTools message must stay well under its
# size limit (a 2048x2048 RGBA32F texture with its mipmaps is 120 MB as one string and ends the
# page).
CHUNK_BYTES = 8 << 20
# Channel textures a page keeps between frames (static images are uploaded once); past this,
# the least recently used ones not bound in the frame at hand are dropped.
KEPT_TEXTURE_BYTES = 1 << 30


def _texture_key(browser: Browser, channel, bound: set[str]) -> str | None:
    """The key of `channel` (a channels.ChannelInput, or None) in the page's textures, uploaded
    first if the page does not hold it: level by level, in chunks of CHUNK_BYTES."""
    if channel is None:
        return None
    key = f"c{channel.serial}"
    bound.add(key)
    kept = browser.textures
    if key in kept:
        kept.move_to_end(key)
        return key
    levels = channel.levels() if channel.filter == "mipmap" else [channel.texels]
    data = [np.ascontiguousarray(t, dtype="<f4").tobytes() for t in levels]
    size = sum(len(d) for d in data)
    old = [k for k in kept if k not in bound]
    while old and sum(kept.values()) + size > KEPT_TEXTURE_BYTES:
        drop = old.pop(0)
        browser.call("textureDrop", [drop])
        del kept[drop]
    h, w = channel.texels.shape[-3:-1]
    sizes = [len(d) for d in data]
    browser.call("textureBegin", key, w, h, channel.filter, channel.wrap, sizes, channel.cube)
    for level, raw in enumerate(data):
        for offset in range(0, len(raw), CHUNK_BYTES):
            text = base64.b64encode(raw[offset : offset + CHUNK_BYTES]).decode("ascii")
            browser.call("textureChunk", key, level, offset, text)
    browser.call("textureEnd", key)
    kept[key] = size
    return key


# ANGLE quotes the token it complains about first: "'=' : cannot convert from ...".
_TOKEN_RE = re.compile(r"^'([^']+)'\s*:")


def angle_diagnostics(program: Program, log: str, stage: str = "compile") -> list[Diagnostic]:
    """ANGLE's errors as diagnostics in the user's files (rule `webgl-compile`).

    ANGLE gives lines, not columns; the column is that of the quoted token when the line has
    it exactly once, else 1. A log with no recognisable message is kept whole.
    """
    if not any(severity == "error" for _, _, severity, _ in parse_driver_log(log)):
        what = "does not link" if stage == "link" else "does not compile"
        return [
            Diagnostic(
                f"WebGL 2 (ANGLE): the {program.tab} program {what}:\n{log.strip()}",
                None,
                rule=RULE,
            )
        ]
    out = []
    for d in driver_diagnostics(program, log):
        d = replace(d, rule=RULE, message=f"WebGL: {d.message}")
        m = _TOKEN_RE.match(d.message.removeprefix("WebGL: "))
        if m and d.loc is not None and d.loc.column == 1:
            text = source_line(d.loc.path, d.loc.line) or ""
            if text.count(m[1]) == 1:
                col = text.index(m[1]) + 1
                d = replace(
                    d, loc=Location(d.loc.path, d.loc.line, col, d.loc.line, col + len(m[1]))
                )
        out.append(d)
    return out


def _compile(browser: Browser, program: Program) -> tuple[int, list[str]]:
    """(program id in the page, active uniform names); GlslError with ANGLE's messages."""
    try:
        result = browser.call("compile", VERTEX_SHADER, program.text)
    except WebGLTimeout as e:
        raise GlslError(
            Diagnostic(
                f"WebGL: compiling the {program.tab} program took more than {e.seconds:g} s "
                "in the browser, which was ended",
                entry_location(program),
                rule=RULE,
            )
        ) from None
    if "id" in result:
        return result["id"], result["active"]
    if "vertexLog" in result:  # our own vertex stage: a broken browser, not the user's shader
        raise GlslError(
            Diagnostic(
                f"WebGL 2 rejected Shadertoy's vertex shader:\n{result['vertexLog']}",
                None,
                rule=RULE,
            )
        )
    stage = "link" if "linkLog" in result else "compile"
    raise GlslError(
        angle_diagnostics(program, result.get("compileLog") or result.get("linkLog") or "", stage)
    )


def webgl_diagnostics(
    shader: Shader, tab: str = "Image", browser: Browser | None = None
) -> list[Diagnostic]:
    """ANGLE's errors for the program Shadertoy compiles for `tab`; [] when it compiles and
    links."""
    browser = browser or get_browser()
    program = build_program(shader, tab, cube=_cube(shader, tab))
    try:
        program_id, _ = _compile(browser, program)
    except GlslError as e:
        return e.diagnostics
    browser.call("release", [program_id])
    return []


@dataclass(eq=False)
class WebGLProgram:
    """A shader compiled by the browser's WebGL 2; render it as often as needed."""

    shader: Shader
    program: Program  # the one-sample program (exactly what Shadertoy compiles)
    browser: Browser
    _variants: dict[bool, int] = field(default_factory=dict, repr=False)
    active_uniforms: list[str] = field(default_factory=list)
    cube: frozenset[str] = frozenset()  # the iChannels declared samplerCube

    def __post_init__(self) -> None:
        # Programs dropped without release() are deleted in the page at the browser's next call.
        weakref.finalize(self, _forget, self.browser, self._variants)

    @property
    def renderer(self) -> str:
        """The WebGL renderer, e.g. 'ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device ...'."""
        return self.browser.info["renderer"]

    def _variant(self, samples_offset: bool) -> int:
        if samples_offset not in self._variants:
            program = build_program(
                self.shader, self.program.tab, samples_offset=samples_offset, cube=self.cube
            )
            self._variants[samples_offset] = _compile(self.browser, program)[0]
        return self._variants[samples_offset]

    @frame_inputs
    def render(self, inputs: FrameInputs, channels=None) -> np.ndarray:
        """One frame: float32 (height, width, 4), row 0 = top; see `GLProgram.render`.

        `channels`: iChannel0..3 as `channels.ChannelInput` or None (unbound), uploaded as
        RGBA32F textures with their filter, wrap and glslcheck's mipmap levels, as on GL
        (glslcheck.backends.multipass.MultipassProgram chains the passes frame after frame)."""
        width, height, samples = inputs.width, inputs.height, inputs.samples
        program_id = self._variant(samples > 1)
        uniforms = uniform_values(
            width,
            height,
            inputs.time,
            inputs.frame,
            inputs.mouse,
            inputs.date,
            inputs.time_delta,
            inputs.frame_rate,
            channels,
        )
        js_offsets = [list(o) if samples > 1 else None for o in inputs.offsets]
        if self.browser.closed:
            raise GlslError(
                Diagnostic(
                    "WebGL: the browser this program was compiled in has ended (after a "
                    "timeout); compile the shader again",
                    None,
                    rule=RULE,
                )
            )
        try:
            bound: set[str] = set()
            js_channels = (
                None
                if channels is None
                else [_texture_key(self.browser, c, bound) for c in channels]
            )
            data = self.browser.call(
                "render", program_id, width, height, uniforms, js_offsets, js_channels
            )
        except WebGLTimeout as e:
            raise GlslError(
                Diagnostic(
                    f"WebGL: the {self.program.tab} program ran for more than {e.seconds:g} s in "
                    "the browser (an "
                    f"endless or very long loop?); the browser was ended",
                    entry_location(self.program),
                    rule=RULE,
                    help="a loop whose count depends on a uniform or a pixel may never end; "
                    "bound it with a "
                    "constant, or raise $GLSLCHECK_WEBGL_TIMEOUT for a slow shader",
                )
            ) from None
        except self.browser.Error as e:
            first = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
            raise GlslError(
                Diagnostic(
                    f"WebGL: rendering the {self.program.tab} program failed: {first}",
                    None,
                    rule=RULE,
                )
            ) from None
        image = np.frombuffer(base64.b64decode(data), dtype="<f4").reshape(height, width, 4)
        return np.ascontiguousarray(image[::-1])  # GL rows go bottom-up; images top-down

    def release(self) -> None:
        """Delete the page's programs (the browser keeps running for the next shader)."""
        ids = list(self._variants.values())
        self._variants.clear()
        if ids and not self.browser.closed:
            self.browser.call("release", ids)


def _cube(shader: Shader, tab: str) -> frozenset[str]:
    """The iChannels the pass samples as cube maps (declared samplerCube, as on GL)."""
    from ...semantics import cube_samplers

    return cube_samplers(shader.units_for(tab), tab) if tab in shader.tabs else frozenset()


def _forget(browser: Browser, variants: dict[bool, int]) -> None:
    browser.pending_release.extend(variants.values())


def compile_webgl(
    shader: Shader, browser: Browser | None = None, *, tab: str = "Image"
) -> WebGLProgram:
    """Compile the Image tab (or plain GLSL file, or a buffer `tab`) of `shader` with WebGL 2.

    GlslError with diagnostics in the user's files when ANGLE rejects it; WebGLUnavailable (an
    InputError, exit 2) when no browser can be started.
    """
    browser = browser or get_browser()
    cube = _cube(shader, tab)
    program = build_program(shader, tab, cube=cube)
    program_id, active = _compile(browser, program)
    webgl = WebGLProgram(
        shader,
        program,
        browser,
        active_uniforms=[n for n in active if not n.startswith("gl_")],
        cube=cube,
    )
    webgl._variants[False] = program_id
    return webgl


def render_shader(shader: Shader, **render_args) -> np.ndarray:
    """Compile and render in one call; `render_args` are those of `WebGLProgram.render`."""
    webgl = compile_webgl(shader)
    try:
        return webgl.render(**render_args)
    finally:
        webgl.release()


__all__ = [
    "OFFSET_UNIFORM",
    "RULE",
    "WebGLProgram",
    "angle_diagnostics",
    "compile_webgl",
    "render_shader",
    "uniform_values",
    "webgl_diagnostics",
]
