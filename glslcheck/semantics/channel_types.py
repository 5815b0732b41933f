"""The sampler type of each iChannel, inferred from how the program samples it.

Shadertoy's wrapper declares `uniform <sampler type of the bound input> iChannelN;`: sampler2D
for a buffer, an image or nothing, samplerCube for a cube map (and sampler3D for a volume). A
shader's text alone does not say what was bound, but its uses do: `texture(iChannel0, dir)` with
a vec3 `dir`, or an argument to a `samplerCube` parameter, only compiles against a cube map.

The rule (used by `glslcheck.semantics.check` for a channel that no channels.json binds; glslcheck's
channels.json binds buffers and images only, which are 2D):

* Every channel is first taken as sampler2D, Shadertoy's type when nothing or an image is bound.
* When that program has errors, each channel read in it is looked at: a *use* is an argument of
  a call. A use is *cube-like* when the call matches with the channel as samplerCube and not as
  sampler2D: a built-in (`texture`, `textureLod`, `textureGrad`, `textureSize`, ...) whose
  overload resolves only with samplerCube given the other arguments' types, or a user function
  whose parameter at that place is declared samplerCube.
* A use is *neutral* when a built-in matches with both (`textureSize(iChannel0, 0)`).
* A channel with one or more cube-like uses and no other use than neutral ones is samplerCube
  and the program is checked again; a channel with any 2D or unclear use stays sampler2D, so
  its errors stand.

Nothing is inferred for sampler3D (no course file needs it), and a program that mixes 2D and cube
uses of one channel keeps the errors of one of them: no binding could make both compile.
"""

from __future__ import annotations

from ..frontend import syntax as A
from ..language import builtin_functions as B
from ..language import glsl_types as T
from .model import ErrorType

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from .model import Model

CHANNELS = tuple(f"iChannel{i}" for i in range(4))
SAMPLER_2D = T.SAMPLERS["sampler2D"]
SAMPLER_CUBE = T.SAMPLERS["samplerCube"]


def cube_channels(model: Model) -> frozenset[str]:
    """The channels a checked program (with errors, from the sampler2D pass) uses only as cube
    maps (see the module docstring)."""
    uses: dict[str, list[bool | None]] = {}
    for call in model.ast.walk():
        if type(call) is not A.Call:
            continue
        for i, arg in enumerate(call.args):
            if type(arg) is A.Identifier and arg.name in CHANNELS:
                sym = model.symbol_of(arg)
                if sym is not None and sym.kind == "uniform":
                    uses.setdefault(arg.name, []).append(_cube_like(model, call, i))
    return frozenset(
        name for name, cube in uses.items() if any(cube) and all(c or c is None for c in cube)
    )


def _cube_like(model: Model, call: A.Call, i: int) -> bool | None:
    """True for a cube-like use, None for a neutral one, False otherwise (module docstring)."""
    if call.array is not None or call.struct_ is not None:
        return False
    if B.is_builtin_function(call.callee) and call.callee not in model.functions:
        types = [model.type_of(a) for a in call.args]
        if any(t is None or isinstance(t, ErrorType) for t in types):
            return False

        def fits(sampler: T.Type) -> bool:
            return isinstance(
                B.resolve(call.callee, types[:i] + [sampler] + types[i + 1 :]), B.Overload
            )

        cube, flat = fits(SAMPLER_CUBE), fits(SAMPLER_2D)
        return None if cube and flat else cube
    overloads = [f for f in model.functions.get(call.callee, []) if len(f.params) == len(call.args)]
    return bool(overloads) and all(f.params[i][1] == SAMPLER_CUBE for f in overloads)
