"""Channels: `channels.json`, image textures, and which pass reads which Buffer.

This module owns the channel bindings of a shader folder; backends/multipass.py runs the passes
frame after frame, and the backends only sample the `ChannelInput`s they are handed (GL:
backends/gl/program.py, NumPy: backends/numpy_engine/textures.py).

channels.json, in the shader's folder (one object per tab that has inputs):

    {"Buffer A": {"iChannel0": {"buffer": "Buffer A"}},
     "Image": {"iChannel0": {"buffer": "Buffer A", "filter": "linear"},
               "iChannel1": {"texture": "tex.png", "filter": "mipmap", "wrap": "repeat", "vflip":
               true}}}

Each binding has `buffer` (a Buffer tab), `texture` (an image path relative to the folder, read
with Pillow) or `cubemap` (a cube map: a folder holding the six faces px, nx, py, ny, pz, nz as
PNG or JPEG files, or the first of six files named as Shadertoy names its cube maps' faces,
`name.png`, `name_1.png` .. `name_5.png` for +X, -X, +Y, -Y, +Z, -Z; square faces of one size),
and optional `filter` (nearest | linear | mipmap; default mipmap for textures,
linear for buffers), `wrap` (clamp | repeat; default repeat for textures, clamp for buffers) and
`vflip` (default true for textures, false for buffers: Shadertoy flips images so that their top
row is at t = 1; a cube map's defaults are Shadertoy's, mipmap, clamp and no flip: its faces'
top rows are at t = 0, as OpenGL's cube maps have them). A cube map accepts only the clamp
wrap: WebGL 2 filters cube maps seamlessly, and seamless filtering ignores the wrap.

Passes, as Shadertoy runs them: every frame renders Buffer A, B, C, D (those the shader has),
then Image. Buffers are RGBA float32 (Shadertoy allocates its buffers as 32-bit float RGBA
textures where the browser can render to them, which WebGL 2 can), sized like the Image,
cleared to zero before frame 0, and double-buffered: a pass reads what earlier passes of this
frame wrote, and its own and later buffers' previous frame. Hence every cycle between buffers is a
feedback and valid; the one cycle that is not (reading the Image tab, which nothing can read
on Shadertoy) is an error. Image files are sampled as RGBA float32 texels (value / 255) on both
backends (docs/llvmpipe.md, "Texture sampling", says why, and what llvmpipe's filtering does).

iChannelResolution[N] is (width, height, 1) of the image or the buffer (the Image's size);
iChannelTime[N] stays 0 for both: Shadertoy's page (effect.js, `EffectPass.Paint_Image`, as kept
in public copies such as DustinBrett/daedalOS public/System/ShaderToy/CoastalLandscape/effect.js)
starts it at 0 and sets it only for video and music inputs (their currentTime) and microphone or
muted music (10 + iTime), none of which glslcheck supports. Tested on all three backends.

Sampler precision: Shadertoy's prelude declares `precision mediump sampler3D;` and nothing for
sampler2D, so iChannel0-3 are declared lowp (the ES 3.00 fragment default) before any user code;
a `precision highp sampler2D;` in the user's tab comes after their declaration and does not
change them (measured: llvmpipe still truncates). glslcheck compiles the same prelude on GL, and
the NumPy backend truncates every lookup as llvmpipe does (backends/numpy_engine/textures.py).

Shadertoy's own JSON export of a shader (`glslcheck render shader.json`, see
`sources.load_shadertoy_json`): the passes' code becomes the tabs and the inputs the bindings,
with `/media/...` files taken from a `media/` folder beside the JSON (a cube map's six faces
with Shadertoy's names).

Errors (InputError, exit 2, naming channels.json and the key): bad JSON, an unknown tab or
key, a missing or unreadable image, an unsupported input kind, bad values. A pass reading an
iChannel its tab does not bind is a GlslError (exit 1) at the read, unless the shader is
Shadertoy's own export: Shadertoy runs such a read (the unit has no texture, it reads (0, 0, 0, 1)
and its size is 0; e.g. the public shader fsXcR8 reads iChannel1 with no input there), and so do
glslcheck's backends.
"""

from __future__ import annotations

import itertools
import json
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..base.diagnostics import InputError, Location
from .bindings import CUBE_FACES, FILTERS, KIND_DEFAULTS, WRAPS, Binding
from .sources import BUFFER_TABS, Shader, read_json
from .wrapper import PASS_TABS

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import NoReturn

CHANNELS_FILE = "channels.json"
KINDS = ("buffer", "texture", "cubemap")
_UNSUPPORTED = ("video", "webcam", "microphone", "music", "sound", "keyboard", "volume")
_SERIAL = itertools.count()
_COMMENT_RE = re.compile(r"/\*.*?(\*/|\Z)|//[^\n]*", re.S)


@dataclass(eq=False)
class ChannelInput:
    """What a backend samples: `texels` float32 (height, width, 4), row 0 at t near 0 (OpenGL's
    first row), or with `cube` (6, size, size, 4), the faces in OpenGL's order +X, -X, +Y, -Y,
    +Z, -Z; `lowp`: lookups return lowp results (always, for Shadertoy's iChannels)."""

    texels: np.ndarray
    filter: str = "linear"
    wrap: str = "clamp"
    lowp: bool = True
    cube: bool = False
    serial: int = field(default_factory=lambda: next(_SERIAL))
    _levels: list | None = field(default=None, repr=False)

    def __repr__(self) -> str:  # unique: the NumPy backend's frame cache keys on it
        return f"ChannelInput#{self.serial}"

    def levels(self) -> list[np.ndarray]:
        """The mipmap levels (level 0 = texels), made once: see `mip_levels`."""
        if self._levels is None:
            if self.cube:  # each face's pyramid, the levels stacked as (6, size, size, 4)
                faces = [mip_levels(f) for f in self.texels]
                self._levels = [np.stack(level) for level in zip(*faces)]
            else:
                self._levels = mip_levels(self.texels)
        return self._levels


def mip_levels(texels: np.ndarray) -> list[np.ndarray]:
    """glslcheck's mipmap pyramid, uploaded as it is to GL too (a driver's glGenerateMipmap is
    implementation-defined): level k+1 is max(1, size >> 1) on each side, each texel the float32
    mean ((a + b) + (c + d)) * 0.25 of its 2x2 block of level k (an odd last row or column is
    left out, as the halved size is rounded down)."""
    levels = [np.ascontiguousarray(texels, dtype=np.float32)]
    while max(levels[-1].shape[:2]) > 1:
        t = levels[-1]
        h, w = t.shape[:2]
        h2, w2 = max(1, h // 2), max(1, w // 2)
        ys = np.minimum(np.arange(h2) * 2, h - 1)
        xs = np.minimum(np.arange(w2) * 2, w - 1)
        ys1, xs1 = np.minimum(ys + 1, h - 1), np.minimum(xs + 1, w - 1)
        a, b = t[ys][:, xs], t[ys][:, xs1]
        c, d = t[ys1][:, xs], t[ys1][:, xs1]
        levels.append(((a + b) + (c + d)) * np.float32(0.25))
    return levels


def channel_uniforms(channels) -> dict:
    """The sampler values and iChannelResolution of iChannel0..3 (None: unbound, size 0)."""
    chans = list(channels) + [None] * (4 - len(channels))
    values = {f"iChannel{i}": c for i, c in enumerate(chans)}
    values["iChannelResolution"] = tuple(
        (0.0, 0.0, 0.0)
        if c is None
        else (float(c.texels.shape[-2]), float(c.texels.shape[-3]), 1.0)
        for c in chans
    )
    return values


def folder_of(shader: Shader) -> Path:
    root = Path(shader.root)
    return root if root.is_dir() else root.parent


def load_bindings(shader: Shader) -> tuple[str | None, list[Binding]]:
    """(path of channels.json or None, its bindings), validated against the shader's tabs; a
    shader read from Shadertoy's JSON export brings its own (`sources.load_shadertoy_json`)."""
    if shader.channels is not None:
        return shader.root, list(shader.channels)
    path = folder_of(shader) / CHANNELS_FILE
    if not path.is_file():
        return None, []
    spath = str(path)
    data = read_json(path)

    def fail(key: str, message: str) -> NoReturn:
        raise InputError(f"{spath}: error: {key}: {message}")

    if not isinstance(data, dict):
        fail(
            "the top level",
            'must be an object of tabs, e.g. {"Image": {"iChannel0": {"buffer": "Buffer A"}}}',
        )
    out: list[Binding] = []
    for tab, chans in data.items():
        if tab not in PASS_TABS:
            fail(json.dumps(tab), f"unknown tab (tabs with inputs: {', '.join(PASS_TABS)})")
        if tab not in shader.tabs:
            fail(json.dumps(tab), f"the shader has no {tab} tab (no '{tab}.glsl' in the folder)")
        if not isinstance(chans, dict):
            fail(json.dumps(tab), "must be an object of channels (iChannel0 .. iChannel3)")
        for key, spec in chans.items():
            where = f"{json.dumps(tab)}.{json.dumps(key)}"
            m = re.fullmatch(r"iChannel([0-3])", key)
            if m is None:
                fail(where, "unknown key (expected iChannel0 .. iChannel3)")
            out.append(_binding(shader, tab, int(m.group(1)), spec, where, fail))
    return spath, out


def _binding(
    shader: Shader, tab: str, channel: int, spec, where: str, fail: Callable[[str, str], NoReturn]
) -> Binding:
    if not isinstance(spec, dict):
        fail(where, 'must be an object with "buffer" or "texture"')
    kinds = [k for k in KINDS if k in spec]
    other = [k for k in spec if k not in (*KINDS, "filter", "wrap", "vflip")]
    for k in other:
        if k in _UNSUPPORTED:
            fail(
                f"{where}.{json.dumps(k)}",
                f"{k} inputs are not supported yet (tab {tab}, iChannel{channel})",
            )
        fail(
            f"{where}.{json.dumps(k)}",
            "unknown key (expected buffer, texture or cubemap, filter, wrap, vflip)",
        )
    if len(kinds) != 1:
        fail(
            where,
            'needs exactly one of "buffer" (a tab), "texture" (an image file) and "cubemap" '
            "(a folder of six faces)",
        )
    kind = kinds[0]
    value = spec[kind]
    if not isinstance(value, str):
        fail(f"{where}.{json.dumps(kind)}", "must be a string")
    if kind == "buffer":
        if value == "Image":
            fail(
                f'{where}."buffer"',
                "the Image tab cannot be an input (a cycle that is no feedback: "
                "Shadertoy offers only Buffer A .. Buffer D)",
            )
        if value not in BUFFER_TABS:
            fail(
                f'{where}."buffer"',
                f"unknown tab {value!r} (expected one of {', '.join(BUFFER_TABS)})",
            )
        if value not in shader.tabs:
            fail(
                f'{where}."buffer"',
                f"the shader has no {value} tab (no '{value}.glsl' in the folder)",
            )
    filt, wrap, vflip = KIND_DEFAULTS[kind]
    filt = spec.get("filter", filt)
    wrap = spec.get("wrap", wrap)
    vflip = spec.get("vflip", vflip)
    if filt not in FILTERS:
        fail(f'{where}."filter"', f"must be one of {', '.join(FILTERS)}, not {json.dumps(filt)}")
    if wrap not in WRAPS:
        fail(f'{where}."wrap"', f"must be one of {', '.join(WRAPS)}, not {json.dumps(wrap)}")
    if not isinstance(vflip, bool):
        fail(f'{where}."vflip"', f"must be true or false, not {json.dumps(vflip)}")
    if kind == "cubemap" and wrap != "clamp":
        fail(
            f'{where}."wrap"',
            "a cube map is sampled seamlessly (as WebGL 2 does), which clamps to the edges: "
            'only "clamp" applies',
        )
    if kind == "cubemap":
        read_cubemap(cube_faces(shader, value, f'{where}."cubemap"', fail), fail)  # fail early
    if kind == "texture":
        texture_path(shader, value, f'{where}."texture"', fail)
        read_image(folder_of(shader) / value, f'{where}."texture"', fail)  # fail early
    return Binding(
        tab,
        channel,
        value if kind == "buffer" else None,
        value if kind != "buffer" else None,
        filt,
        wrap,
        vflip,
        kind == "cubemap",
    )


def texture_path(shader: Shader, name: str, where: str, fail) -> Path:
    """The file a texture binding names: inside the shader's folder (no absolute path, no `..`
    or symlink out of it), so a shared channels.json reads no other file of the user's."""
    folder = folder_of(shader).resolve()
    path = folder / name
    if Path(name).is_absolute() or not path.resolve().is_relative_to(folder):
        fail(
            where,
            f"{name!r} is outside the shader's folder; textures are read from the folder "
            f"of the shader (copy the image there)",
        )
    return path


def cube_faces(shader: Shader, name: str, where: str, fail) -> list[tuple[Path, str]]:
    """The six face files of a cube binding, +X, -X, +Y, -Y, +Z, -Z, each with its key for an
    error: a folder's px, nx, py, ny, pz, nz (.png, .jpg or .jpeg), or `name.ext` and Shadertoy's
    `name_1.ext` .. `name_5.ext` beside it."""
    path = texture_path(shader, name, where, fail)
    if path.is_dir():
        found = []
        for stem in CUBE_FACES:
            files = sorted(
                p
                for p in path.iterdir()
                if p.stem.lower() == stem and p.suffix.lower() in (".png", ".jpg", ".jpeg")
            )
            if len(files) != 1:
                what = "no" if not files else "more than one"
                fail(
                    where,
                    f"{what} {stem} face in the folder {str(path)!r} (a cube map folder holds "
                    f"{', '.join(CUBE_FACES)} as .png, .jpg or .jpeg files)",
                )
            rel = str(Path(name) / files[0].name)
            found.append((texture_path(shader, rel, where, fail), where))
        return found
    if not path.exists():
        fail(
            where,
            f"no such file or folder {str(path)!r} (a cube map is a folder of px, nx, py, ny, "
            "pz, nz images, or Shadertoy's name.png, name_1.png .. name_5.png)",
        )
    stem, suffix = name[: len(name) - len(path.suffix)], path.suffix
    names = [name] + [f"{stem}_{k}{suffix}" for k in range(1, 6)]
    return [(texture_path(shader, n, where, fail), where) for n in names]


def read_cubemap(faces: list[tuple[Path, str]], fail) -> np.ndarray:
    """The faces as RGBA float32 (6, size, size, 4), each face's first row its image's top; a
    face that is missing, not square or of another size than the first is an error naming it."""
    out: list[np.ndarray] = []
    for path, where in faces:
        t = read_image(path, where, fail)
        h, w = t.shape[:2]
        if h != w:
            fail(where, f"the cube map face {str(path)!r} is {w}x{h}, not square")
        if out and t.shape != out[0].shape:
            n = out[0].shape[0]
            fail(
                where,
                f"the cube map face {str(path)!r} is {w}x{h}, the first face "
                f"{str(faces[0][0])!r} is {n}x{n} (all six must be the same size)",
            )
        out.append(t)
    return np.stack(out)


def read_image(path: Path, where: str, fail) -> np.ndarray:
    """RGBA float32 (height, width, 4), first row = the image's top, values v / 255. Only a
    regular file is opened (a FIFO would block the read)."""
    import stat

    from PIL import Image

    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        fail(where, f"no such file {str(path)!r}")
    except OSError as e:
        fail(where, f"cannot read the image {str(path)!r} ({e.strerror or e})")
    if not stat.S_ISREG(mode):
        fail(where, f"{str(path)!r} is not a regular file")
    try:
        with Image.open(path) as im:
            rgba = np.asarray(im.convert("RGBA"), dtype=np.float32)
    except (OSError, ValueError) as e:
        fail(where, f"cannot read the image {str(path)!r} ({e})")
    except (
        Exception
    ) as e:  # Pillow's decoders raise other types on a damaged or hostile file (bombs too)
        fail(where, f"cannot read the image {str(path)!r} ({type(e).__name__}: {e})")
    return rgba / np.float32(255.0)


def channel_reads(shader: Shader, tab: str) -> dict[int, Location]:
    """The iChannels the pass's code names, each with where it first does (comments skipped)."""
    found: dict[int, Location] = {}
    for src in shader.units_for(tab):
        code = _COMMENT_RE.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), src.text)
        for m in re.finditer(r"\biChannel([0-3])\b", code):
            n = int(m.group(1))
            if n not in found:
                line = code.count("\n", 0, m.start()) + 1
                col = m.start() - (code.rfind("\n", 0, m.start()) + 1) + 1
                found[n] = Location(src.path, line, col, line, col + len(m.group(0)))
    return found


def needs_passes(shader: Shader) -> bool:
    """Whether the shader has buffers, bindings (a channels.json, or a Shadertoy JSON export's
    inputs), or reads an iChannel. A JSON export of an Image pass with no inputs that reads no
    channel is one pass, as the same code in a .glsl file is."""
    if "GLSL" in shader.tabs:
        return False
    if shader.channels:
        return True
    return (
        any(t in shader.tabs for t in BUFFER_TABS)
        or (shader.channels is None and (folder_of(shader) / CHANNELS_FILE).is_file())
        or ("Image" in shader.tabs and bool(channel_reads(shader, "Image")))
    )


def input_files(shader: Shader) -> list[Path]:
    """Every file rendering the shader reads: its tabs, its channels.json and the textures it
    binds (a command's output must be none of them)."""
    files = [Path(src.path) for src in shader.sources()]
    try:
        path, bindings = load_bindings(shader)
    except InputError:
        return files  # the render reports it
    if path is not None:
        files.append(Path(path))
    for b in bindings:
        if b.texture is None:
            continue
        if not b.cube:
            files.append(folder_of(shader) / b.texture)
            continue
        try:
            files += [p for p, _ in cube_faces(shader, b.texture, "", _raise)]
        except InputError:
            pass  # the render reports it
    return files


def _raise(key: str, message: str) -> NoReturn:
    raise InputError(f"{key}: {message}")
