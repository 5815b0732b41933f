"""WebGL 2's rules beyond GLSL ES 3.00: what ANGLE (the compiler in Shadertoy's browser) rejects
although glslangValidator and Mesa accept it.

Shadertoy users hit ANGLE, so the checker follows it. Each rule was found by compiling the same
Shadertoy program with all four judges (tools/webgl_agreement.py, docs/webgl.md) and is pinned by
a fixture in tests/webgl/invalid that ANGLE must reject at the same line (tests/webgl). The checker
calls these functions; each returns (message, help) for an error, or None. The checker reports them
as errors in Shadertoy tabs and as warnings in a plain GLSL ES file (own #version and main), which
need not run in WebGL.

- Names starting with `webgl_` or `_webgl_` are reserved by WebGL (WebGL 1.0 spec 6.23; ANGLE:
  "reserved built-in name").
- Names containing `__`: GLSL ES 3.00 (3.8) reserves them "for use by underlying software
  layers" and says declaring one "does not itself result in an error"; glslangValidator (with a
  warning) and Mesa accept them, and ANGLE rejects them ("identifiers containing two consecutive
  underscores (__) are reserved as possible future keywords", the wording of GLSL ES 1.00 3.7),
  so no browser compiles such a shader. Like the other rules, an error in a Shadertoy tab and a
  warning in a plain file (measured: docs/webgl.md). Macro names with `__` are the
  preprocessor's (a warning: ANGLE accepts `#define A__B`).
- Names longer than 1024 characters: WebGL 2's limit (spec 4.17 of WebGL 2); glslang and Mesa
  have theirs too.
- `?:` whose branches are structs or arrays (WebGL 1.0 spec 6.26, kept by ANGLE for WebGL 2:
  "ternary operator is not allowed for structures/arrays in ESSL 1.0 and webgl").
- Interface blocks laid out `shared` or `packed` ("Only std140 layout is allowed in WebGL").
"""

from __future__ import annotations

MAX_NAME_LENGTH = 1024
RESERVED_PREFIXES = ("webgl_", "_webgl_")
BLOCK_LAYOUTS = ("shared", "packed")


def name_problem(name: str) -> tuple[str, str] | None:
    if name.startswith(RESERVED_PREFIXES):
        prefix = next(p for p in RESERVED_PREFIXES if name.startswith(p))
        return (
            f"'{name}': names starting with '{prefix}' are reserved by WebGL (Shadertoy's "
            "browser rejects it)",
            f"rename it, for example to '{name[len(prefix) :] or 'value'}'",
        )
    if "__" in name:
        return (
            f"'{name}': names containing '__' are reserved in GLSL ES (Shadertoy's browser "
            "rejects it)",
            f"rename it, for example to '{name.replace('__', '_').strip('_') or 'value'}'",
        )
    if len(name) > MAX_NAME_LENGTH:
        return (
            f"'{name[:20]}...': a name of {len(name)} characters; "
            f"WebGL allows at most {MAX_NAME_LENGTH}",
            "use a shorter name",
        )
    return None


def ternary_problem(branch_type) -> tuple[str, str] | None:
    from ..language.glsl_types import StructType

    kind = (
        "arrays"
        if branch_type.is_array
        else "structs"
        if isinstance(branch_type, StructType)
        else None
    )
    if kind is None:
        return None
    return (
        f"WebGL does not allow '?:' on {kind} ('{branch_type}')",
        "use if/else and assign the variable in each branch",
    )


def block_layout_problem(layout_ids) -> tuple[str, str] | None:
    bad = [i for i in layout_ids if i in BLOCK_LAYOUTS]
    if not bad:
        return None
    return (
        f"WebGL allows only the std140 layout for uniform blocks, not '{bad[0]}'",
        "write layout(std140) or leave the layout out",
    )
