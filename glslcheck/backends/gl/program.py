"""Compiling a Shadertoy shader for the GL driver and rendering it into a float framebuffer.

`compile_gl(shader)` wraps the Image tab (or a plain GLSL file) as Shadertoy does
(`glslcheck.shadertoy.wrapper.build_program`), compiles it with the driver and turns a driver error
log into `GlslError` diagnostics located in the user's own files. `GLProgram.render(...)` draws a
full-screen triangle into an RGBA32F framebuffer and returns the pixels as float32
(height, width, 4), top row first, neither clamped nor quantised.

Inputs, and what glslcheck feeds them (see `glslcheck.shadertoy.wrapper.UNIFORMS`):

- iResolution = (width, height, 1); iTime, iFrame, iMouse, iTimeDelta, iFrameRate from `render`.
- iDate = `date`, by default the fixed `DEFAULT_DATE` (2026, 0, 1, 0.0) = 2026-01-01 00:00:00,
  so renders are reproducible. Give a tuple (year, month 0-11, day, seconds) or a `datetime`.
- iChannelTime all 0 (Shadertoy's value for images and buffers, shadertoy/channels.py), iSampleRate
  44100; without `channels` iChannelResolution all 0 and iChannel0..3 unbound (texture() then
  returns (0, 0, 0, 1), GL's value for an incomplete texture).
- Uniforms the shader does not use are skipped (the driver drops inactive uniforms, and trims
  arrays to the highest index used).

Supersampling: `samples = k*k` renders k*k times with fragCoord moved by the sub-pixel offset
((i + 0.5)/k - 0.5, (j + 0.5)/k - 0.5), i, j = 0..k-1, and averages. The offset is a uniform
`glslcheck_offset` that the footer adds (`mainImage(color, gl_FragCoord.xy + glslcheck_offset)`);
it exists only in the program compiled for samples > 1, so a one-sample render runs exactly the
program Shadertoy runs. The average is taken in float64 and rounded to float32 once.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...base.diagnostics import GlslError
from ...shadertoy.frame_inputs import FrameInputs, frame_inputs
from ...shadertoy.sources import Shader
from ...shadertoy.wrapper import OFFSET_UNIFORM, UNIFORMS, UNIFORMS_BY_NAME, Program, build_program
from ..driver_log import driver_diagnostics
from ..driver_profile import driver_model
from .context import get_context, gl_function
from .zero_init import zero_initialized

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    import moderngl

# A triangle that covers the viewport, from gl_VertexID alone (no vertex buffer):
# ids 0, 1, 2 -> (-1, -1), (3, -1), (-1, 3).
VERTEX_SHADER = """#version 300 es
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
"""


@dataclass(eq=False)
class _Compiled:
    """One driver program and the vertex array that draws it."""

    program: Program
    gl_program: moderngl.Program
    vao: moderngl.VertexArray


@dataclass(eq=False)
class GLProgram:
    """A shader compiled for the GL driver; render it as often as needed."""

    shader: Shader
    program: Program  # the one-sample program (exactly what Shadertoy compiles)
    ctx: moderngl.Context
    _variants: dict[bool, _Compiled] = field(default_factory=dict, repr=False)
    cube: frozenset[str] = frozenset()  # the iChannels declared samplerCube

    @property
    def float_to_uint_model(self) -> str | None:
        """How this driver computes uint(x) where the CPU decides
        (glslcheck/backends/driver_profile.py), measured once per context; None when it follows no
        known model."""
        return driver_model(self.ctx)

    @property
    def active_uniforms(self) -> list[str]:
        """The uniforms the driver kept (those the shader actually uses)."""
        prog = self._variants[False].gl_program
        return [name for name in prog if not name.startswith("gl_")]

    def _variant(self, samples_offset: bool) -> _Compiled:
        if samples_offset not in self._variants:
            program = build_program(
                self.shader, self.program.tab, samples_offset=samples_offset, cube=self.cube
            )
            self._variants[samples_offset] = _compile(self.ctx, program)
        return self._variants[samples_offset]

    @frame_inputs
    def render(self, inputs: FrameInputs, channels=None) -> np.ndarray:
        """Render one frame: float32 array (height, width, 4), row 0 = top of the image.

        Arguments: `shadertoy.FrameInputs` (size=(width, height), time, frame, mouse, date,
        time_delta, frame_rate, samples), then `channels`. `date`: see the module docstring
        (default 2026-01-01 00:00). `samples` must be a perfect square; see the module docstring
        for the sub-pixel grid. Values are what the shader wrote (RGBA32F): not clamped to
        [0, 1], not quantised; the Image pass has alpha 1.
        """
        width, height, samples, offsets = (
            inputs.width,
            inputs.height,
            inputs.samples,
            inputs.offsets,
        )
        compiled = self._variant(samples > 1)
        values = inputs.uniforms()
        channel_textures = []
        if channels is not None:  # `channels`: iChannel0..3 as channels.ChannelInput or None
            from ...shadertoy.channels import channel_uniforms

            values.update(channel_uniforms(channels))
            values.update({f"iChannel{i}": i for i in range(4)})
        prog = compiled.gl_program
        for u in UNIFORMS:
            _set_uniform(prog, u.name, values.get(u.name, u.default), u.array_size)

        ctx = self.ctx
        texture = ctx.texture((width, height), 4, dtype="f4")
        fbo = ctx.framebuffer(color_attachments=[texture])
        try:
            channel_textures = [
                _bind_channel(ctx, unit, c)
                for unit, c in enumerate(channels or ())
                if c is not None
            ]
            fbo.use()
            total = None
            for dx, dy in offsets:
                if samples > 1:
                    _set_uniform(prog, OFFSET_UNIFORM, (dx, dy))
                fbo.clear(0.0, 0.0, 0.0, 0.0)
                compiled.vao.render(vertices=3)
                data = np.frombuffer(fbo.read(components=4, dtype="f4"), dtype=np.float32)
                img = data.reshape(height, width, 4)
                total = img.astype(np.float64) if total is None else total + img
        finally:
            fbo.release()
            texture.release()
            for t in channel_textures:
                t.release()
        assert total is not None  # at least one sample offset
        image = (total / len(offsets)).astype(np.float32)
        return np.ascontiguousarray(image[::-1])  # GL rows go bottom-up; images top-down


# GL_TEXTURE_CUBE_MAP_SEAMLESS: off by default in a desktop GL context, always on in OpenGL ES 3
# and WebGL 2, where Shadertoy runs
_CUBE_MAP_SEAMLESS = 0x884F
_CUBE_FACE_0, _RGBA, _FLOAT = 0x8515, 0x1908, 0x1406  # GL_TEXTURE_CUBE_MAP_POSITIVE_X ..


def _bind_channel(ctx, unit: int, channel):
    """Upload a channels.ChannelInput as an RGBA32F texture on `unit` with its filter and wrap.
    Its texels' row 0 is texture coordinate t near 0, which is OpenGL's first row."""
    import moderngl

    if channel.cube:
        return _bind_cube(ctx, unit, channel)
    h, w = channel.texels.shape[:2]
    tex = ctx.texture(
        (w, h), 4, np.ascontiguousarray(channel.texels, dtype=np.float32).tobytes(), dtype="f4"
    )
    if (
        channel.filter == "mipmap"
    ):  # glslcheck's own pyramid (channels.mip_levels), as the NumPy side
        tex.build_mipmaps()  # allocates the levels
        for level, texels in enumerate(channel.levels()[1:], 1):
            tex.write(np.ascontiguousarray(texels).tobytes(), level=level)
        tex.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
    else:
        mode = moderngl.NEAREST if channel.filter == "nearest" else moderngl.LINEAR
        tex.filter = (mode, mode)
    tex.repeat_x = tex.repeat_y = channel.wrap == "repeat"
    tex.use(unit)
    return tex


def _bind_cube(ctx, unit: int, channel):
    """A cube map channel as an RGBA32F TextureCube (faces +X, -X, +Y, -Y, +Z, -Z, each face's
    row 0 its first row), filtered seamlessly as on WebGL 2; its wrap is clamp to edge."""
    import ctypes

    import moderngl

    ctx.enable_direct(_CUBE_MAP_SEAMLESS)
    n = channel.texels.shape[1]
    data = np.ascontiguousarray(channel.texels, dtype=np.float32).tobytes()
    tex = ctx.texture_cube((n, n), 4, data, dtype="f4")
    if channel.filter == "mipmap":  # glslcheck's own pyramid per face, as the NumPy side
        tex.build_mipmaps()  # allocates the levels; moderngl writes level 0 only
        tex.use(unit)
        sub_image = gl_function(  # (target, level, x, y, width, height, format, type, data)
            "glTexSubImage2D",
            *[ctypes.c_uint] + [ctypes.c_int] * 5,
            *[ctypes.c_uint] * 2,
            ctypes.c_void_p,
        )
        for level, texels in enumerate(channel.levels()[1:], 1):
            for face in range(6):
                face_texels = np.ascontiguousarray(texels[face], dtype=np.float32)
                k = face_texels.shape[0]
                address = face_texels.ctypes.data
                sub_image(_CUBE_FACE_0 + face, level, 0, 0, k, k, _RGBA, _FLOAT, address)
        tex.filter = (moderngl.LINEAR_MIPMAP_LINEAR, moderngl.LINEAR)
    else:
        mode = moderngl.NEAREST if channel.filter == "nearest" else moderngl.LINEAR
        tex.filter = (mode, mode)
    tex.use(unit)
    return tex


# GL's type enums of the GLSL types Shadertoy's uniforms have.
_GL_TYPES = {
    "float": 0x1406,
    "int": 0x1404,
    "vec2": 0x8B50,
    "vec3": 0x8B51,
    "vec4": 0x8B52,
    "sampler2D": 0x8B5E,
    "sampler3D": 0x8B5F,
    "samplerCube": 0x8B60,
}


def _set_uniform(gl_program, name: str, value, array_size: int | None = None) -> None:
    """Set a uniform if the driver kept it. The driver trims an array to the highest index the
    shader uses (and reports a one-element array as a plain uniform), so arrays are cut to fit."""
    if name not in gl_program:
        return
    uniform = gl_program[name]
    expected = _GL_TYPES.get(UNIFORMS_BY_NAME[name].glsl_type) if name in UNIFORMS_BY_NAME else None
    if name.startswith("iChannel") and expected == _GL_TYPES["sampler2D"]:
        expected = getattr(uniform, "gl_type", expected)  # sampler2D or samplerCube: a unit
    if expected is not None and getattr(uniform, "gl_type", expected) != expected:
        # a plain file's uniform of another type: not fed, 0 as on NumPy (shadertoy.fed_uniform)
        return
    if array_size:
        items = list(value)[: max(uniform.array_length, 1)]
        value = (
            items[0]
            if len(items) == 1
            else (items if isinstance(items[0], tuple) else tuple(items))
        )
    uniform.value = value


def _compile(ctx, program: Program) -> _Compiled:
    import moderngl

    try:
        gl_program = ctx.program(vertex_shader=VERTEX_SHADER, fragment_shader=program.text)
    except moderngl.Error as e:
        raise GlslError(driver_diagnostics(program, str(e))) from None
    vao = ctx.vertex_array(gl_program, [])
    return _Compiled(program, gl_program, vao)


def compile_gl(shader: Shader, ctx=None, *, tab: str = "Image") -> GLProgram:
    """Compile the Image tab (or plain GLSL file) of `shader` with the GL driver.

    Raises GlslError with diagnostics in the user's files when the driver rejects it, and
    GLUnavailable (an InputError) when no context can be created. `ctx` defaults to the
    process-wide context. `tab` may name a buffer ("Buffer A"): it renders as a single pass
    with alpha kept; its iChannels are unbound unless `render(channels=...)` binds them
    (glslcheck.backends.multipass.MultipassProgram chains the passes frame after frame).
    """
    from ...semantics import cube_samplers

    ctx = ctx if ctx is not None else get_context()
    cube = cube_samplers(shader.units_for(tab), tab) if tab in shader.tabs else frozenset()
    zeroed = zero_initialized(shader, tab)  # WebGL zeroes struct locals; Mesa does not
    if zeroed is not shader:
        try:
            program = build_program(zeroed, tab, cube=cube)
            gl = GLProgram(zeroed, program, ctx, cube=cube)
            gl._variants[False] = _compile(ctx, program)
            return gl
        except GlslError:
            pass  # the driver's own errors come from the user's text, compiled below
    program = build_program(shader, tab, cube=cube)
    gl = GLProgram(shader, program, ctx, cube=cube)
    gl._variants[False] = _compile(ctx, program)
    return gl


def render_shader(shader: Shader, **render_args) -> np.ndarray:
    """Compile and render in one call; `render_args` are those of `GLProgram.render`."""
    return compile_gl(shader).render(**render_args)
