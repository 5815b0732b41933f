"""Channel bindings: which buffer, image or cube map an iChannel of a tab reads, and how it is
sampled.

A `Binding` is one entry of a shader's `channels.json` (read by shadertoy/channels.py) or one
input of Shadertoy's JSON export (read by shadertoy/sources.py); both readers share the
vocabulary here: the filters, the wraps and each input kind's defaults.
"""

from __future__ import annotations

from dataclasses import dataclass

FILTERS = ("nearest", "linear", "mipmap")
WRAPS = ("clamp", "repeat")
# (filter, wrap, vflip) of an input that leaves them out, by kind
# (Shadertoy's: a cube map is not flipped, and WebGL 2 filters cube maps seamlessly, which makes
# the wrap clamp to edge whatever is asked: OpenGL ES 3.0 section 3.8.10)
KIND_DEFAULTS = {
    "texture": ("mipmap", "repeat", True),
    "buffer": ("linear", "clamp", False),
    "cubemap": ("mipmap", "clamp", False),
}
# A cube map's faces in OpenGL's order (+X, -X, +Y, -Y, +Z, -Z), as the file stems of a folder.
CUBE_FACES = ("px", "nx", "py", "ny", "pz", "nz")


@dataclass(frozen=True, slots=True)
class Binding:
    """One entry of channels.json: iChannel`channel` of `tab` reads `buffer` or `texture` (an
    image, or with `cube` a cube map: a folder of faces or the first of Shadertoy's six files)."""

    tab: str
    channel: int
    buffer: str | None
    texture: str | None  # the path as written, relative to the folder
    filter: str
    wrap: str
    vflip: bool
    cube: bool = False
