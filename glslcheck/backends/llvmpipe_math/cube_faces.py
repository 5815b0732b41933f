"""Which texel of which face a cube map lookup reads when a filter's texel falls off a face:
Mesa 22.3's lp_build_cube_new_coords (gallivm, lp_bld_sample.c) as tables, read by the NumPy
engine's cube_maps.py over lanes and the compiled engine's texture_kernels.py for one pixel,
so both seam the faces alike (measured: tests/gl/test_cube_maps.py)."""

from __future__ import annotations

import numpy as np

# lp_build_cube_new_coords as tables, per face 0..5, for a texel that falls off the face at
# x < 0, x > max, y < 0, y > max (in this order): the face it is read from, and its new x and y
# there as pairs (a, b): a * max + b * the coordinate along the other axis (y for an x
# fall-off, x for a y fall-off), max the level's size - 1.
_M, _O, _N, _Z = (1, 0), (0, 1), (1, -1), (0, 0)  # max, the coordinate, max - it, 0
# per fall-off direction, per face: (new face, new x rule, new y rule)
_FALL_OFF = [
    [(4, _M, _O), (5, _M, _O), (1, _O, _Z), (1, _N, _M), (1, _M, _O), (0, _M, _O)],
    [(5, _Z, _O), (4, _Z, _O), (0, _N, _Z), (0, _O, _M), (0, _Z, _O), (1, _Z, _O)],
    [(2, _M, _N), (2, _Z, _O), (5, _N, _Z), (4, _O, _M), (2, _O, _M), (2, _N, _Z)],
    [(3, _M, _O), (3, _Z, _N), (4, _O, _Z), (5, _N, _M), (3, _O, _Z), (3, _N, _M)],
]
NEXT_FACE = np.array([[f for f, _, _ in row] for row in _FALL_OFF], np.int64)
NEXT_X = np.array([[x for _, x, _ in row] for row in _FALL_OFF], np.int64)
NEXT_Y = np.array([[y for _, _, y in row] for row in _FALL_OFF], np.int64)
