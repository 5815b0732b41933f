"""What the texture kernel tests share: the NumPy backend's lookups as the reference, channels
packed as the compiled engine packs them, and float32 bits to compare (every NaN one pattern)."""

from __future__ import annotations

import numpy as np

F = np.float32


def reference():
    """The NumPy backend's lookups (textures.TextureFunctions) in float32 with llvmpipe's rules:
    what the compiled engine's one-pixel kernels (texture_kernels.py) must give bit for bit."""
    from glslcheck.backends.numpy_engine.textures import TextureFunctions

    class Reference(TextureFunctions):
        F = np.float32
        lp = object()  # llvmpipe's float32 mode: lowp arithmetic in float16

    return Reference()


def packed(channel, slot: int):
    """(uf, ui, tm): `channel` bound at iChannel<slot>, packed by texture_kernels.pack behind a
    few other uniforms, as a generated module holds it."""
    from glslcheck.backends.compiled_engine import texture_kernels as tk

    floats, meta = tk.pack([None] * slot + [channel], 3)
    uf = np.concatenate([np.zeros(3, F), floats])
    ui = np.concatenate([np.zeros(5, np.int32), meta])
    return uf, ui, 5


def bits(a):
    a = np.asarray(a, F)
    return np.where(np.isnan(a), np.uint32(0x7FC00000), a.view(np.uint32))
