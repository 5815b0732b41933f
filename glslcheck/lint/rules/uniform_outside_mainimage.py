"""A Shadertoy uniform is read in a function other than mainImage.

## What it does
Reports every reference to a Shadertoy uniform (`iResolution`, `iTime`, `iTimeDelta`,
`iFrameRate`, `iFrame`, `iChannelTime`, `iChannelResolution`, `iMouse`, `iDate`,
`iSampleRate`, `iChannel0`..`iChannel3`), or to a uniform the shader declares itself
(`uniform sampler2D diffuseMap;`), inside any function but `mainImage`, one finding per
reference. A local variable or parameter that shadows a uniform's name (`float iTime = ...`) is
not a uniform and is not reported.

## Why is this bad?
The course's coding standards: "Do not reference uniforms in functions other than 'mainImage'
(-1 per instance): Use the 'mainImage' function provided to call your effect functions. Any
uniform value to be used in a function must be passed as a parameter when the function is
called from 'mainImage'." A function that reads only its parameters can be reused, tested with
other values, and moved to the Common tab (where only `iDate` and `iSampleRate` exist).

## Example
```glsl
vec3 lightPosition()
{
    return vec3(cos(iTime), 1.0, sin(iTime));
}
```

## Use instead
```glsl
vec3 lightPosition(in float time)
{
    return vec3(cos(time), 1.0, sin(time));
}
// in mainImage: vec3 light = lightPosition(iTime);
```
"""

from __future__ import annotations

from ...frontend import syntax as A
from ...semantics.analysis import program_facts
from ..fixes import Fixable
from ..fixes.uniforms import uniform_fix

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Iterator

    from ...base.diagnostics import Diagnostic
    from ..engine import LintContext
    from ..fixes import Fix

NAME = "uniform-outside-mainimage"
PENALTY = 1
STANDARD = "uniforms"
SEVERITY = "warning"
NEEDS = "ast"
READS = "names"  # a function with a compile error is still read: uniforms are names

ENTRY = "mainImage"


def check(ctx: LintContext) -> Iterator[Diagnostic]:
    model = ctx.model
    if model is None:  # (no semantic model: no function has facts)
        return
    fixes: dict[int, Fix | None] = {}  # one fix per uniform, shared by its findings
    for fn in program_facts(model).in_file(ctx.path, with_broken=True):
        name = fn.definition.proto.name
        if name == ENTRY:
            continue
        for node in fn.nodes:
            if type(node) is not A.Identifier:
                continue
            sym = model.symbol_of(node)
            if sym is None or not (
                sym.kind == "uniform" or (sym.kind == "global" and sym.qualifier == "uniform")
            ):
                continue
            if id(sym) not in fixes:
                fixes[id(sym)] = uniform_fix(ctx, sym)
            yield Fixable(
                f"the uniform '{node.name}' is read in '{name}', not in mainImage",
                node.loc,
                help=f"add a parameter to '{name}' and pass {node.name} to it from mainImage",
                fix=fixes[id(sym)],
            )
