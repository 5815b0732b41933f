"""Buffer A-D and Image of one shader on one backend, run frame after frame as Shadertoy runs them
(the schedule and the bindings: glslcheck/shadertoy/channels.py).

`MultipassProgram` compiles each pass through its Backend record's `compile_pass` and hands each
pass the `ChannelInput`s its channels.json binds: the buffers other passes wrote, image textures.
"""

from __future__ import annotations

import numpy as np

from ..base.diagnostics import Diagnostic, GlslError, InputError
from ..shadertoy.channels import (
    CHANNELS_FILE,
    ChannelInput,
    channel_reads,
    cube_faces,
    folder_of,
    load_bindings,
    read_cubemap,
    read_image,
    texture_path,
)
from ..shadertoy.sources import Shader
from ..shadertoy.wrapper import PASS_TABS
from .interface import Backend


class MultipassProgram:
    """Buffer A-D and Image of one shader on one backend, carried from frame to frame.

    `render(size=..., time=..., frame=N, ...)` returns the `output` pass of frame N (default the
    Image). Frames continue the previous render when `frame` is the next one at the same size;
    otherwise the buffers are cleared and frames 0 .. N-1 run first (iTime = time - (N - i) *
    time_delta), so the buffers hold what Shadertoy's would after N frames.
    """

    def __init__(self, shader: Shader, backend: Backend, output: str = "Image") -> None:
        if not backend.multipass:
            raise InputError(
                f"{shader.root}: error: buffers, channels and --pass are not supported on the "
                f"{backend.name} backend; use --backend numpy, gl or webgl"
            )
        self.shader = shader
        self.backend = backend
        self.channels_path, bindings = load_bindings(shader)
        self.passes = [t for t in PASS_TABS if t in shader.tabs]
        if output not in self.passes:
            raise InputError(
                f"{shader.root}: error: --pass {output!r}: the shader has no such tab "
                f"(it has {', '.join(self.passes)})"
            )
        self.output = output
        self.bindings = {t: {b.channel: b for b in bindings if b.tab == t} for t in self.passes}
        self._check_reads()
        self._check_kinds()
        self.textures = {}
        for b in bindings:
            if b.texture is not None:

                def fail(key, message, b=b):
                    raise InputError(f"{self.channels_path}: error: {key}: {message}")

                if b.cube:
                    where = f'"{b.tab}"."iChannel{b.channel}"."cubemap"'
                    self.textures[b.texture, True] = read_cubemap(
                        cube_faces(shader, b.texture, where, fail), fail
                    )
                    continue
                where = f'"{b.tab}"."iChannel{b.channel}"."texture"'
                self.textures[b.texture, False] = read_image(
                    texture_path(shader, b.texture, where, fail), where, fail
                )
        self.programs = {t: self._compile(t) for t in self.passes}
        # Lookups return lowp results as llvmpipe's do (backends/numpy_engine/textures.py); False
        # gives the exact float32 results SwiftShader's WebGL returns (it ignores lowp, measured).
        self.lowp_samplers = True
        self._state: dict[str, np.ndarray] = {}
        self._images: dict[tuple, ChannelInput] = {}
        self._key: tuple[int, int, str | None] | None = None  # (width, height, precision)
        self._next = 0

    @property
    def engine(self) -> str:
        """The engine that rendered the output pass's last frame (Program.engine): under the
        default CPU program each pass moves to the compiled engine on its own (tiered.py)."""
        engine = getattr(self.programs[self.output], "engine", None)
        return engine if isinstance(engine, str) else self.backend.name

    def _check_reads(self) -> None:
        if self.shader.channels is not None:
            # Shadertoy's own export: Shadertoy runs a read of a channel without an input (the
            # unit has no texture: (0, 0, 0, 1), size 0), so glslcheck does too
            return
        diags = []
        for tab in self.passes:
            for n, loc in sorted(channel_reads(self.shader, tab).items()):
                if n not in self.bindings[tab]:
                    where = (
                        self.channels_path or f"{folder_of(self.shader) / CHANNELS_FILE} (missing)"
                    )
                    diags.append(
                        Diagnostic(
                            f"iChannel{n} is read but not bound: {where} has no "
                            f'"{tab}": {{"iChannel{n}": ...}}',
                            loc,
                            rule="unbound-channel",
                        )
                    )
        if diags:
            raise GlslError(diags)

    def _check_kinds(self) -> None:
        """A channel bound to a cube map must be sampled as one (samplerCube, which both the
        GL and the CPU programs declare from the uses: semantics.cube_samplers), and one
        sampled as a cube map must be bound to one: on Shadertoy either would not compile."""
        from ..semantics import cube_samplers

        diags = []
        for tab in self.passes:
            cube = cube_samplers(self.shader.units_for(tab), tab)
            for n, loc in sorted(channel_reads(self.shader, tab).items()):
                b = self.bindings[tab].get(n)
                if b is None or b.cube == (f"iChannel{n}" in cube):
                    continue
                what = (
                    "bound to a cube map but not sampled as one (texture(iChannel{n}, dir) with "
                    "a vec3 direction)"
                    if b.cube
                    else "sampled as a cube map (with a vec3 direction) but bound to a "
                    + ("buffer" if b.buffer is not None else "2D image")
                )
                diags.append(
                    Diagnostic(
                        f"iChannel{n} is {what.format(n=n)}: see "
                        f'{self.channels_path}, "{tab}": {{"iChannel{n}": ...}}',
                        loc,
                        rule="channel-type",
                    )
                )
        if diags:
            raise GlslError(diags)

    def _compile(self, tab: str):
        return self.backend.compile_pass(self.shader, tab)

    # -- what verify and the api look for on a backend program
    @property
    def program(self):  # GL: the output pass's Program (its text)
        return self.programs[self.output].program

    @property
    def source(self) -> str:
        return self.programs[self.output].source

    @property
    def float_to_uint_model(self):
        return self.programs[self.output].float_to_uint_model

    def emulate_float_to_uint(self, model: str) -> None:
        for p in self.programs.values():
            if hasattr(p, "emulate_float_to_uint"):  # the NumPy side only
                p.emulate_float_to_uint(model)

    def format_stats(self) -> str:
        return self.programs[self.output].format_stats()

    def _inputs(self, tab: str) -> list:
        chans: list[ChannelInput | None] = []
        for n in range(4):
            b = self.bindings[tab].get(n)
            if b is None:
                chans.append(None)
                continue
            if b.buffer is None:
                chans.append(self._image_input(b))
                continue
            # buffers are stored bottom row first, images top row first (unflipped, as uploaded)
            texels = self._state[b.buffer][::-1] if b.vflip else self._state[b.buffer]
            chans.append(
                ChannelInput(np.ascontiguousarray(texels), b.filter, b.wrap, self.lowp_samplers)
            )
        return chans

    def _image_input(self, b) -> ChannelInput:
        """An image channel, made once for all frames and passes: its mipmap levels are computed
        once, and a backend that keeps textures (WebGL) uploads it once."""
        key = (b.texture, b.cube, b.vflip, b.filter, b.wrap, self.lowp_samplers)
        if key not in self._images:
            texels = self.textures[b.texture, b.cube]
            if b.vflip:  # an image's rows, or each cube face's
                texels = texels[:, ::-1] if b.cube else texels[::-1]
            self._images[key] = ChannelInput(
                np.ascontiguousarray(texels), b.filter, b.wrap, self.lowp_samplers, b.cube
            )
        return self._images[key]

    def render(
        self,
        size=(800, 450),
        time: float = 0.0,
        frame: int = 0,
        time_delta: float = 1.0 / 60.0,
        samples: int = 1,
        **rest,
    ) -> np.ndarray:
        """One frame of the output pass; arguments as the backend's render (see the class)."""
        if self.backend.driver:
            if rest.pop("precision", "float32") != "float32":
                raise ValueError(
                    f"the {self.backend.name} backend renders in float32 only (the driver's highp)"
                )
            rest.pop("stats", None)
        width, height = int(size[0]), int(size[1])
        key = (width, height, rest.get("precision"))
        if key != self._key or frame != self._next:
            self._state = {
                t: np.zeros((height, width, 4), np.float32) for t in self.passes if t != "Image"
            }
            self._key, self._next = key, 0
        out = None
        while self._next <= frame:
            i = self._next
            t = time - (frame - i) * time_delta
            for tab in self.passes:
                img = self.programs[tab].render(
                    size=(width, height),
                    time=t,
                    frame=i,
                    time_delta=time_delta,
                    samples=samples if tab == "Image" else 1,
                    channels=self._inputs(tab),
                    **rest,
                )
                if tab != "Image":
                    self._state[tab] = np.ascontiguousarray(
                        img[::-1]
                    )  # row 0 = bottom, as GL stores it
                if tab == self.output:
                    out = img
            self._next = i + 1
        assert out is not None  # frame >= 0: the loop ran at least once
        return out
