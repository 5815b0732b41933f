"""The constants of llvmpipe's math: gallivm's (lp_bld_arit.c, Mesa 22.3) and Mesa's NIR lowerings
of atan, asin and acos, as Python floats and one float32 table.

Every emulation of these algorithms reads them from here: the NumPy reference
(numpy_engine/llvmpipe_reference.py), its fast kernels (numpy_engine/llvmpipe_fast.py) and the
numba one-lane functions (:mod:`.lane`).
"""

from __future__ import annotations

import numpy as np

# lp_build_sin_or_cos: 4/pi, the three parts of pi/4 (DP1..DP3) and the cosine's polynomial
# (column 0) beside the sine's (column 1)
FOUR_OVER_PI = 1.27323954473516
DP = (-0.78515625, -2.4187564849853515625e-4, -3.77489497744594108e-8)
SIN_COS = np.array(
    [
        [2.443315711809948e-005, -1.9515295891e-4],
        [-1.388731625493765e-003, 8.3321608736e-3],
        [4.166664568298827e-002, -1.6666654611e-1],
    ],
    dtype=np.float32,
)[:, :, None]
# |x| below 2**29 (bits 0x4E000000) keeps j = int(|x| * 4/pi) + 1 far from int32 overflow
# (cvttps2dq's INT_MIN case) and excludes Inf and NaN
SIN_MAX_BITS = 0x4E000000

# lp_build_exp2: the clamp of the argument, and lp_build_exp2_polynomial, EXP_POLY_DEGREE 5 (the
# first coefficient is 1.0 exactly)
EXP2_HI, EXP2_LO = 128.0, -126.99999
EXP2 = (
    1.0,
    0.693153073200168932794,
    0.240153617044375388211,
    0.0558263180532956664775,
    0.00898934009049466391101,
    0.00187757667519147912699,
)

# lp_build_log2_polynomial, LOG_POLY_DEGREE 4
LOG2 = (
    2.88539009343309178325,
    0.961791550404184197881,
    0.577440339438736392009,
    0.403343858251329912514,
    0.406718052498846252698,
)

# float32 bit patterns the algorithms test
ABS_BITS = 0x7FFFFFFF  # every bit but the sign
MIN_NORMAL_BITS = 0x00800000  # FLT_MIN: below, a nonzero |x| is subnormal
INF_BITS = 0x7F800000

# Mesa's nir_atan: the odd polynomial of atan on [0, 1], x^1 to x^11
ATAN = (
    0.9999793128310355,
    -0.3326756418091246,
    0.1938924977115610,
    -0.1173503194786851,
    0.0536813784310406,
    -0.0121323213173444,
)
# atan(y, x) scales |t| >= 1e18 by 1/4 (so that 1/t stays a normal float)
ATAN2_BIG, ATAN2_SCALE = 1e18, 0.25
# Mesa's asin/acos: pi/2 - sqrt(1 - |x|) * (pi/2 + |x| * (pi/4 - 1 + |x| * (p0 + |x| * p1)))
ASIN_P = (0.086566724, -0.03102955)
ACOS_P = (0.08132463, -0.02363318)
