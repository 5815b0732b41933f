"""Channel bindings: which buffer or image an iChannel of a tab reads, and how it is sampled.

A `Binding` is one entry of a shader's `channels.json` (read by shadertoy/channels.py) or one
input of Shadertoy's JSON export (read by shadertoy/sources.py); both readers share the
vocabulary here: the filters, the wraps and each input kind's defaults.
"""

from __future__ import annotations

from dataclasses import dataclass

FILTERS = ("nearest", "linear", "mipmap")
WRAPS = ("clamp", "repeat")
# (filter, wrap, vflip) of an input that leaves them out, by kind
KIND_DEFAULTS = {"texture": ("mipmap", "repeat", True), "buffer": ("linear", "clamp", False)}


@dataclass(frozen=True, slots=True)
class Binding:
    """One entry of channels.json: iChannel`channel` of `tab` reads `buffer` or `texture`."""

    tab: str
    channel: int
    buffer: str | None
    texture: str | None  # the path as written, relative to the folder
    filter: str
    wrap: str
    vflip: bool
