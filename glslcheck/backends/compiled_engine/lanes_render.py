"""The fixed text of a lockstep module (lanes.py): its math imports, and its render loop: rows cut
into blocks of W pixels, or into 2x2 quads for a module with derivatives, each block one call of
the shading function, its samples summed as the per-pixel loop sums them."""

from __future__ import annotations

import importlib.util
from typing import Any

STATE_LANES = ("gf", "gi", "gu", "gb")  # per-pixel state: one array per lane
# shade's fragCoord.y and pixel centre y: one value for a block (a row's)
ROW_UNIFORM = ("fy", "py")
MATH = tuple(
    f"glslcheck.backends.compiled_engine.{m}" for m in ("scalar", "lanes_math")
)  # later wins


def math_imports() -> list[str]:
    """The generated module's math imports: scalar.py's names, then lanes_math.py's (when that
    module exists) over them."""
    out = []
    for name in MATH:
        if importlib.util.find_spec(name) is not None:
            out.append(f"from {name} import *  # noqa: F401,F403")
    return out


def rt_hash() -> str:
    """The hash of lanes.py, select_chains.py, lanes_render.py, lanes_rt.py and lanes_math.py
    (when it exists): numba's cache does not see a callee's change, the engine's module key (a
    hash of the source) does."""
    import hashlib
    import os

    h = hashlib.sha256()
    here = os.path.dirname(__file__)
    for name in ("lanes_rt.py", "lanes.py", "select_chains.py", "lanes_render.py", "lanes_math.py"):
        path = os.path.join(here, name)
        if os.path.exists(path):
            with open(path, "rb") as f:
                h.update(f.read())
    return h.hexdigest()[:16]


def quad_lanes(name: str, k: int, W: int) -> tuple[int, int]:
    """The lanes whose difference is lane k's derivative (`dfdx`/`dfdy`) in a block of 2x2
    quads: lanes 0..W/2-1 are the lower row (even y, counted from the bottom as gl_FragCoord),
    W/2..W-1 the row above, each row from an even x. As llvmpipe (fine derivatives,
    backends/numpy_engine/runtime.py Runtime.dFdx): dFdx(x, y) = v(x|1, y) - v(x&~1, y), dFdy(x, y)
    = v(x, y|1) - v(x, y&~1). `qdx`/`qdy` (texture_calls.py): the differences from the quad's
    bottom-left pixel to its right and upper neighbours, the same for the quad's four pixels
    (textures._quad_corner_diff: llvmpipe's implicit LOD)."""
    h = W // 2
    c, r = k % h, k // h
    if name == "dfdx":
        return r * h + (c | 1), r * h + (c & ~1)
    if name == "qdx":  # the quad's x difference on its lower row, for all four of its pixels
        return c | 1, c & ~1
    if name == "qdy":  # and its y difference on its left column: a mipmap lookup's implicit LOD
        return h + (c & ~1), c & ~1
    return h + c, c


def render_source(
    W: int,
    resets: Any = None,
    shade: str = "shade",
    scalar: Any = (),
    ret_uniform: Any = (),
    quads: bool = False,
) -> str:
    """render_rows for blocks of W pixels of a row (the last block repeats the row's last pixel);
    resets: the state arrays reset before each block, those a function writes (None: all of
    them; constant_globals.reset_kinds: the others hold the template all frame); shade: the
    entry's name, scalar: its parameters passed as one value for the block (ROW_UNIFORM),
    ret_uniform: which of its four results are one value for the block.

    quads: blocks of W/2 pixels of two rows (y even, y + 1; quad_lanes), y0 even. At an odd
    right or top edge the quad's other pixels are llvmpipe's helper invocations outside the
    image (x = width, y = height: computed, not written, as the NumPy backend's tiles); a quad
    wholly past the right edge repeats the row's last whole quad."""
    if quads:
        return _render_quads(W, resets, shade, ret_uniform)
    st = [f"{a}__{k}" for a in STATE_LANES for k in range(W)]
    lines = _prologue(
        W,
        [
            '    """Rows y0..y1-1 (counted from the bottom) into out (height, width, 4), '
            "top row first,",
            f'    {W} pixels of a row a call of shade; offs: the (dx, dy) sample offsets."""',
        ],
    )
    lines += [
        "    for y in range(y0, y1):",
        "        row = height - 1 - y",
        "        py = F32(y + 0.5)",
        f"        for x0 in range(0, width, {W}):",
    ]
    for k in range(W):
        lines.append(f"            px__{k} = F32(min(x0 + {k}, width - 1) + 0.5)")
    lines += _sample_head(W, resets)
    lines.append("                oy = F32(py + F32(offs[s, 1]))")
    args = ["True"] * W + st + ["uf", "ui", "lc"]
    args += [f"F32(px__{k} + ox)" for k in range(W)] + (["oy"] if "fy" in scalar else ["oy"] * W)
    args += [f"px__{k}" for k in range(W)] + (["py"] if "py" in scalar else ["py"] * W)
    lines.append(f"                res = {shade}({', '.join(args)})")
    lines += _accumulate(W, ret_uniform)
    lines += [
        f"            for k in range(min({W}, width - x0)):",
        "                for c in range(4):",
        "                    out[row, x0 + k, c] = acc[c, k] / samples",
        "    loops_limited(lt, lc)",
    ]
    return "\n".join(lines)


def _prologue(W: int, doc: list[str]) -> list[str]:
    """render_rows (its per-lane state copies and accumulator), then the signature of the loop
    it calls (module_text's rows_loop: no reference counts), up to its body."""
    sig = "def render_rows(out, y0, y1, width, height, offs, uf, ui, gtf, gti, gtu, gtb, lt):"
    head = ["@numba.njit(cache=True, nogil=True, error_model='numpy')", sig]
    lines = head + doc + ["    lc = acopy(lt)"]  # the loop budget: per block (scalar.tick)
    state = [f"{a}__{k}" for a in STATE_LANES for k in range(W)]
    for a, t in zip(STATE_LANES, ("gtf", "gti", "gtu", "gtb")):
        lines += [f"    {a}__{k} = acopy({t})" for k in range(W)]
    params = ", ".join(
        ["out, y0, y1, width, height, offs, uf, ui, gtf, gti, gtu, gtb, lt, lc, acc", *state]
    )
    return lines + [
        f"    acc = np.zeros((4, {W}), np.float64)",
        f"    rows_loop({params})",
        "",
        "",
        "@jit_loop",
        f"def rows_loop({params}):",
        '    """render_rows\' blocks, with its state copies and accumulator."""',
        "    samples = offs.shape[0]",
    ]


def _sample_head(W: int, resets: Any) -> list[str]:
    """The loop over the samples: the per-pixel state reset to its template before each call of
    shade, and the sample's x offset."""
    lines = ["            for s in range(samples):"]
    for a, t in zip(STATE_LANES, ("gtf", "gti", "gtu", "gtb")):
        if resets is not None and a not in resets:
            continue
        lines += [f"                aset({a}__{k}, 0, {t})" for k in range(W)]
    return lines + ["                lc[0] = lt[0]", "                ox = F32(offs[s, 0])"]


def _accumulate(W: int, ret_uniform: Any) -> list[str]:
    """The samples' sum of shade's result `res` into acc (4, W)."""
    at, start = {}, 0  # (channel, lane) -> its index in shade's result (a uniform channel: one)
    for c in range(4):
        one = bool(ret_uniform and ret_uniform[c])
        for k in range(W):
            at[c, k] = start if one else start + k
        start += 1 if one else W
    lines = ["                if s == 0:  # the sum of one sample is its value (a -0.0 kept)"]
    lines += [
        f"                    acc[{c}, {k}] = np.float64(res[{at[c, k]}])"
        for c in range(4)
        for k in range(W)
    ]
    lines.append("                else:")
    lines += [
        f"                    acc[{c}, {k}] = acc[{c}, {k}] + res[{at[c, k]}]"
        for c in range(4)
        for k in range(W)
    ]
    return lines


def _render_quads(W: int, resets: Any, shade: str, ret_uniform: Any) -> str:
    """render_source for blocks of 2x2 quads (derivatives): see render_source."""
    h = W // 2
    st = [f"{a}__{k}" for a in STATE_LANES for k in range(W)]
    lines = _prologue(
        W,
        [
            '    """Rows y0..y1-1 (counted from the bottom; y0 even) into out (height, width, '
            "4), top row",
            f"    first, 2x2 quads: {h} pixels of two rows a call of shade; offs: "
            'the sample offsets."""',
        ],
    )
    lines += [
        "    last = (width - 1) & ~1  # the last whole quad's left column",
        "    for y in range(y0, y1, 2):",
        "        py0 = F32(y + 0.5)",
        "        py1 = F32(y + 1.5)  # y + 1 = height: a helper row",
        f"        for x0 in range(0, width, {h}):",
    ]
    for c in range(h):
        lines.append(
            f"            px__{c} = F32((x0 + {c} if x0 + {c & ~1} < width else last + {c & 1}) "
            "+ 0.5)"
        )
    lines += _sample_head(W, resets)
    lines += [
        "                oy0 = F32(py0 + F32(offs[s, 1]))",
        "                oy1 = F32(py1 + F32(offs[s, 1]))",
    ]
    px = [f"px__{k % h}" for k in range(W)]
    args = ["True"] * W + st + ["uf", "ui", "lc"]
    args += [f"F32({p} + ox)" for p in px] + ["oy0"] * h + ["oy1"] * h
    args += px + ["py0"] * h + ["py1"] * h
    lines.append(f"                res = {shade}({', '.join(args)})")
    lines += _accumulate(W, ret_uniform)
    lines += [
        "            for r in range(2):",
        "                if y + r >= height:",
        "                    break",
        f"                for k in range(min({h}, width - x0)):",
        "                    for c in range(4):",
        "                        out[height - 1 - y - r, x0 + k, c] = acc[c, "
        f"r * {h} + k] / samples",
        "    loops_limited(lt, lc)",
    ]
    return "\n".join(lines)
