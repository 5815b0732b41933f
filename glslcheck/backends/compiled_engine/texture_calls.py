"""Texture lookups in the compiled engine: the ES 3.00 built-ins on a sampler2D, and texture,
textureLod, textureGrad and textureSize on a samplerCube (a cube map channel), as calls of
backends/compiled_engine/texture_kernels.py (the one-pixel form of the NumPy backend's
textures.py), and arithmetic on lowp lookups in float16 where the NumPy backend computes it so
(nir_fold.lower_precision: llvmpipe's float16 lowering).

A sampler is one int leaf, its channel number (iChannelN is the constant N; a sampler parameter
passes it on). The texels and each channel's filter, wrap and sizes are read at run time from
the tails of the uniform arrays `uf` and `ui` (engine.py packs them each frame; `TM`, a module
constant, is where the channels' words start in `ui`). The implicit LOD of a mipmap channel's
`texture()` reads the differences of the coordinates across the 2x2 quad (`qdx`/`qdy`, which
only the lockstep rewrite computes, lanes.py): the generator is told which channels are bound
with mipmaps (`Codegen.mipmap`), and a lookup on any other channel reads level 0 without them.
A cube map's implicit LOD is per pixel, from the direction's fine derivatives (`dfdx`/`dfdy`, as
dFdx: textures.py and cube_maps.py)."""

from __future__ import annotations

from typing import Any

from ...frontend import syntax as A
from ..cpu_core.common import CUBE_FUNCTIONS, TEXTURE_FUNCTIONS
from ..cpu_core.nir_fold.lower_precision import float16_code, float16_lookup_args, float16_tree
from .values import Val, not_yet


def _layout(name: str) -> tuple[str, bool, bool]:
    """A sampling lookup's argument layout after the sampler, from its name: how its LOD comes
    ("implicit" | "explicit" | "grad"), whether its coordinate is divided (Proj), whether an
    offset follows."""
    lod = "grad" if "Grad" in name else "explicit" if "Lod" in name else "implicit"
    return lod, "Proj" in name, name.endswith("Offset")


KERNELS = (
    "tex_sample, tex_lod, tex_fetch, tex_size, tex_lowp, half, tex_sample_cube, tex_lod_cube, "
    "lowp_const"
)
IMPORT = f"from glslcheck.backends.compiled_engine.texture_kernels import {KERNELS}  # noqa: F401"


def channel_of(cg: Any, sampler: Any) -> int | None:
    """The channel number of an iChannelN operand, None for a sampler parameter."""
    sym = cg.model.symbol_of(sampler) if isinstance(sampler, A.Identifier) else None
    if sym is not None and sym.kind in ("uniform", "global") and sym.name.startswith("iChannel"):
        return int(sym.name[len("iChannel") :])
    return None


def texture_call(cg: Any, e: A.Call, name: str) -> Val:
    """A lookup built-in (common.TEXTURE_FUNCTIONS) on a sampler2D, or (common.CUBE_FUNCTIONS)
    on a samplerCube."""
    stype = str(cg.type_of(e.args[0]))
    if stype == "samplerCube" and name in CUBE_FUNCTIONS and name != "textureSize":
        return _cube_call(cg, e, name)
    if stype not in ("sampler2D", "samplerCube") or (
        stype == "samplerCube" and name not in CUBE_FUNCTIONS
    ):
        raise not_yet(f"{name}(): '{stype}' lookups", e)
    cg.textures = True
    rtype = cg.type_of(e)
    ch = cg.atom(cg.expr(e.args[0]).parts[0])
    args = _args(cg, e, ch)
    if name == "textureSize":
        t = cg.tmp_fresh(f"tex_size(ui, TM, {ch}, {args[0].parts[0]})")
        return Val(rtype, [f"{t}[0]", f"{t}[1]"])
    if name in ("texelFetch", "texelFetchOffset"):
        x, y = args[0].parts
        if name == "texelFetchOffset":
            ox, oy = args[2].parts
            x, y = f"(np.int64({x}) + {ox})", f"(np.int64({y}) + {oy})"
        t = cg.tmp_fresh(f"tex_fetch(uf, ui, TM, {ch}, {x}, {y}, {args[1].parts[0]})")
        return Val(rtype, [f"{t}[{i}]" for i in range(4)])
    if name not in TEXTURE_FUNCTIONS:
        raise not_yet(f"{name}()", e)
    lod_kind, proj, has_offset = _layout(name)
    p = [cg.atom(x) for x in args[0].parts]
    u, v = p[0], p[1]
    if proj:  # p.xy / p.z (vec3) or p.xy / p.w (vec4), in float32
        u, v = cg.tmp(f"({u} / {p[-1]})"), cg.tmp(f"({v} / {p[-1]})")
    rest = args[1:]
    offset = ("0", "0")
    if has_offset:  # the offset comes after the LOD or the gradients
        at = {"implicit": 0, "explicit": 1, "grad": 2}[lod_kind]
        offset = tuple(rest[at].parts)
        rest = rest[:at] + rest[at + 1 :]
    has_lod, lod = "False", "F32(0.0)"
    if lod_kind == "explicit":
        has_lod, lod = "True", rest[0].parts[0]
    elif lod_kind == "grad":
        gx, gy = rest[0].parts, rest[1].parts
        has_lod = "True"
        lod = cg.tmp_fresh(f"tex_lod(ui, TM, {ch}, {gx[0]}, {gx[1]}, {gy[0]}, {gy[1]}, True)")
    elif lod_kind == "implicit" and not _needs_lod(cg, e.args[0]):
        # level 0, right for a channel without mipmaps (the engine refuses one with them)
        cg.level0_lookups |= _channels(cg, e.args[0])
    elif lod_kind == "implicit":
        if cg.derivative is None:
            cg.derivative = e  # the quads' differences: lockstep only, as dFdx
        d = [
            cg.tmp_fresh(f"{f}({c if c.isidentifier() else cg.tmp_fresh(c)})")
            for f in ("qdx", "qdy")
            for c in (u, v)
        ]
        has_lod = "True"
        lod = cg.tmp_fresh(f"tex_lod(ui, TM, {ch}, {d[0]}, {d[1]}, {d[2]}, {d[3]}, False)")
        if rest:  # the bias, added to the implicit LOD
            lod = cg.tmp_fresh(f"({lod} + {rest[0].parts[0]})")
    t = cg.tmp_fresh(
        f"tex_sample(uf, ui, TM, {ch}, {u}, {v}, {offset[0]}, {offset[1]}, {has_lod}, {lod})"
    )
    return Val(rtype, [f"{t}[{i}]" for i in range(4)])


def _cube_call(cg: Any, e: A.Call, name: str) -> Val:
    """texture(samplerCube, vec3[, bias]), textureLod or textureGrad: tex_sample_cube at the
    direction, with the explicit LOD, the given derivatives' (tex_lod_cube), a mipmapped
    channel's implicit one (tex_lod_cube from the direction's fine derivatives, lockstep only),
    or level 0."""
    cg.textures = True
    rtype = cg.type_of(e)
    ch = cg.atom(cg.expr(e.args[0]).parts[0])
    args = _args(cg, e, ch)
    d = [cg.atom(x) for x in args[0].parts]
    has_lod, lod, implicit = "False", "F32(0.0)", "False"
    if name == "textureLod":
        has_lod, lod = "True", args[1].parts[0]
    elif name == "textureGrad":  # (a channel without mipmaps ignores the LOD)
        grads = ", ".join(cg.atom(x) for a in args[1:3] for x in a.parts)
        has_lod, implicit = "True", "True"
        lod = cg.tmp_fresh(f"tex_lod_cube(ui, TM, {ch}, {', '.join(d)}, {grads}, True)")
    elif not _needs_lod(cg, e.args[0]):
        cg.level0_lookups |= _channels(cg, e.args[0])
    else:
        if cg.derivative is None:
            cg.derivative = e  # the pixels' fine differences: lockstep only, as dFdx
        names = [c if c.isidentifier() else cg.tmp_fresh(c) for c in d]
        diffs = [cg.tmp_fresh(f"{f}({c})") for f in ("dfdx", "dfdy") for c in names]
        has_lod, implicit = "True", "True"
        lod = cg.tmp_fresh(f"tex_lod_cube(ui, TM, {ch}, {', '.join(names + diffs)}, False)")
        if len(args) > 1:  # the bias, added to the implicit LOD
            lod = cg.tmp_fresh(f"({lod} + {args[1].parts[0]})")
        d = names
    t = cg.tmp_fresh(
        f"tex_sample_cube(uf, ui, TM, {ch}, {d[0]}, {d[1]}, {d[2]}, {has_lod}, {lod}, {implicit})"
    )
    return Val(rtype, [f"{t}[{i}]" for i in range(4)])


def _args(cg: Any, e: A.Call, ch: str) -> list[Val]:
    """The values of a lookup's arguments after the sampler, each constant one that a lowp
    sampler reads rounded to float16 wrapped in lowp_const (nir_fold.float16_lookup_args)."""

    args = [cg.expr(a) for a in e.args[1:]]
    for i in float16_lookup_args(cg.fold_context(), e):
        v = args[i - 1]
        args[i - 1] = Val(v.t, [cg.tmp_fresh(f"lowp_const(ui, TM, {ch}, {p})") for p in v.parts])
    return args


def _needs_lod(cg: Any, sampler: Any) -> bool:
    """Whether an implicit-LOD lookup on this sampler may read mipmaps: its channel is bound
    with them, or (a sampler parameter) a channel its callers may pass is."""
    chans = _channels(cg, sampler)
    return bool(cg.mipmap) if -1 in chans else bool(chans & cg.mipmap)


def _channels(cg: Any, sampler: Any) -> set[int]:
    """The channels a sampler operand may be: {N} for iChannelN, what the callers pass for a
    sampler parameter (sampler_flow), {-1} when that is not known."""
    ch = channel_of(cg, sampler)
    if ch is not None:
        return {ch}
    sym = cg.model.symbol_of(sampler) if isinstance(sampler, A.Identifier) else None
    if sym is None or sym.kind != "param" or cg.fn is None or cg.fn.sym is None:
        return {-1}
    return sampler_flow(cg).get((id(cg.fn.sym), sym.name), set())


def sampler_flow(cg: Any) -> dict[tuple[int, str], set[int]]:
    """(id of a function, name of its sampler parameter) -> the channels its calls pass
    there: an iChannel directly or through the caller's own sampler parameter (a fixpoint;
    GLSL has no recursion)."""
    if cg.sampler_flow is not None:
        return cg.sampler_flow
    from ...semantics.model import Symbol

    edges: list[tuple[tuple[int, str], Any, Any]] = []  # (callee's key, caller, argument)
    for fn in cg.functions:
        for n in fn.node.body.walk():
            tgt = cg.model.call_target(n) if isinstance(n, A.Call) else None
            if not isinstance(tgt, Symbol) or not tgt.params:
                continue
            for a, (pname, ptype, _) in zip(n.args, tgt.params):
                if str(ptype) in ("sampler2D", "samplerCube"):
                    edges.append(((id(tgt), pname), fn, a))
    flow: dict[tuple[int, str], set[int]] = {}
    changed = True
    while changed:
        changed = False
        for key, caller, a in edges:
            ch = channel_of(cg, a)
            if ch is not None:
                got = {ch}
            elif isinstance(a, A.Identifier):
                got = flow.get((id(caller), a.name), set())
            else:
                got = set()
            if not got <= flow.setdefault(key, set()):
                flow[key] |= got
                changed = True
    cg.sampler_flow = flow
    return flow


# -- float16 arithmetic on lowp lookups ------------------------------------------------------
def lowp_tree(cg: Any, e: A.Binary) -> Val | None:
    """`e` as the NumPy backend computes it (nir_fold.lower_precision.float16_tree): in float16
    when it is such a tree and every sampler it reads is lowp (tex_lowp, at run time), else
    in float32 (the written form); None when e is no such tree."""

    if cg.fn is None or cg.fn.sym is None or id(e) in cg.lowp_written:
        return None
    found = float16_tree(cg.fold_context(), e)
    if found is None:
        return None
    ops, samplers = found
    chans = list(dict.fromkeys(cg.atom(cg.expr(s).parts[0]) for s in samplers))
    cond = cg.tmp_fresh(" and ".join(f"tex_lowp(ui, TM, {c})" for c in chans))
    rtype = cg.type_of(e)
    out = [cg.fresh() for _ in range(_size(rtype))]
    for name in out:  # (written first outside the branches: lockstep selects under masks)
        cg.emit(f"{name} = F32(0.0)")
    cg.emit(f"if {cond}:")
    cg.indent += 1
    low = float16_code(cg.model, e, ops, _Float16Parts(cg, len(out)))
    for name, part in zip(out, low):
        cg.emit(f"{name} = {part}")
    cg.indent -= 1
    cg.emit("else:")
    cg.indent += 1
    cg.lowp_written |= ops
    try:
        written = cg.expr(e).parts
    finally:
        cg.lowp_written -= ops
    for name, part in zip(out, written):
        cg.emit(f"{name} = {part}")
    cg.indent -= 1
    return Val(rtype, out)


def _size(t: Any) -> int:
    return 1 if t.is_scalar else t.size


class _Float16Parts:
    """The compiled engine's float16 tree (lower_precision.float16_code writes it): the n float32
    components of each value, a leaf's rounded to float16 (`half`) and each operation one
    float32 operation rounded to float16 (exact for these: a float32 result of two float16
    operands rounds to the float16 one); every component a name, so a value read twice is
    computed once."""

    def __init__(self, cg: Any, n: int) -> None:
        self.cg, self.n = cg, n

    def leaf(self, node: Any) -> list[str]:
        parts = [self.cg.atom(f"half({p})") for p in self.cg.expr(node).parts]
        return parts if len(parts) == self.n else parts * self.n

    def negate(self, x: list[str]) -> list[str]:
        return [f"(-{v})" for v in x]

    def op(self, op: str, a: list[str], b: list[str]) -> list[str]:
        return [self.cg.atom(f"half({x} {op} {y})") for x, y in zip(a, b)]

    def shared(self, build: Any) -> tuple[list[str], list[str]]:
        x = build()
        return x, x
