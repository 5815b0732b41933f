"""WebGL's zero initialisation of struct locals and out parameters, which Mesa's `glsl_zero_init`
leaves out.

Shadertoy runs on WebGL, which initialises every local variable to zero. The GL backend asks
Mesa for the same with the driconf option `glsl_zero_init` (see context.py), but Mesa applies
it to numeric and bool types only (ast_to_hir.cpp: `type->is_numeric() || is_boolean()`): a
struct local, or an array of structs, stays undefined, and llvmpipe then folds reads of it to
arbitrary values. Measured: `L one[2]; one[1].k + 3.0` renders 0, not 3; a GPR-200 Lab 4
submission that fills two of five `pLight lights[5]` renders black on llvmpipe where WebGL
and the NumPy backend agree on NaN from the unset lights.

`zero_initialized(shader, tab)` returns the shader with ` = S(...)` written after each such
declarator (same line, so every line number stays), or the shader itself when there is none;
the GL backend compiles that. Declarators produced by a macro are left alone.
"""

from __future__ import annotations

from ...frontend import syntax as A
from ...language import glsl_types as T
from ...shadertoy.sources import Shader, Source


def zero_text(t: T.Type) -> str | None:
    """A constant expression of type t with every component zero (None if t has none)."""
    if isinstance(t, T.StructType):
        parts = [zero_text(ft) for _, ft in t.fields]
        known = [p for p in parts if p is not None]
        return None if len(known) < len(parts) else f"{t.name}({', '.join(known)})"
    if isinstance(t, T.ArrayType):
        if t.array_size is None:
            return None
        inner = zero_text(t.element)
        return None if inner is None else f"{t}({', '.join([inner] * t.array_size)})"
    base = {"float": "0.0", "int": "0", "uint": "0u", "bool": "false"}.get(t.base or "")
    if base is None:
        return None
    name = str(t)
    return base if name in ("float", "int", "uint", "bool") else f"{name}({base})"


def _struct_locals(model, tree) -> list[tuple[A.Declarator, str]]:
    """(declarator, zero text) for local declarations of struct (or struct-array) type without
    initializer."""
    found = []
    for node in tree.walk():
        if not isinstance(node, A.FunctionDefinition):
            continue
        for decl in node.walk():
            if not isinstance(decl, A.Declarator) or decl.init is not None:
                continue
            sym = model.symbol_of(decl)
            t = getattr(sym, "type", None)
            if t is None:
                continue
            element = t.element if t.is_array else t
            text = zero_text(t) if element.is_struct else None
            if text is not None:
                found.append((decl, text))
    return found


def _out_params(model, tree) -> list[tuple[A.Compound, str]]:
    """(function body, `p = zero;` statements) for functions with `out` parameters, which
    Mesa also leaves undefined on entry (measured: reading one before writing it gives 0
    where WebGL and the NumPy backend read zero and compute). mainImage is left alone: the
    Shadertoy footer's argument is its concern."""
    found = []
    for node in tree.walk():
        if not isinstance(node, A.FunctionDefinition) or node.body is None or node.proto is None:
            continue
        if node.proto.name == "mainImage":
            continue
        stmts = []
        for param in node.proto.params:
            sym = model.symbol_of(param)
            text = zero_text(sym.type) if sym is not None and param.direction == "out" else None
            if text is not None and param.name:
                stmts.append(f" {param.name} = {text};")
        if stmts:
            found.append((node.body, "".join(stmts)))
    return found


def zero_initialized(shader: Shader, tab: str = "Image") -> Shader:
    """The shader with its uninitialised struct locals given zero initialisers (see module)."""
    try:
        from ...frontend.parser import parse_units
        from ...semantics import check

        units = shader.units_for(tab)
        if any(u.is_plain_glsl for u in units):
            return shader
        parsed = parse_units(units)
        model = check(parsed, tab)
    except Exception:  # the driver reports whatever our own front end cannot read
        return shader
    edits: dict[str, list[tuple[int, int, str]]] = {}
    for decl, text in _struct_locals(model, parsed.ast):
        loc = decl.loc
        if loc is None or loc.end_line != loc.line or loc.end_column is None:
            continue
        row = _line(shader, loc.path, loc.line)
        if row is None or not row[loc.column - 1 :].startswith(decl.name):
            continue  # not the user's own text here (a macro expansion)
        edits.setdefault(loc.path, []).append((loc.line, loc.end_column, f" = {text}"))
    for body, text in _out_params(model, parsed.ast):
        loc = body.loc
        row = _line(shader, loc.path, loc.line) if loc is not None else None
        if row is None or not row[loc.column - 1 :].startswith("{"):
            continue
        edits.setdefault(loc.path, []).append((loc.line, loc.column + 1, text))
    if not edits:
        return shader
    tabs = {}
    for name, src in shader.tabs.items():
        changes = edits.get(src.path)
        if not changes:
            tabs[name] = src
            continue
        lines = src.text.split("\n")
        for line, col, text in sorted(changes, reverse=True):
            row = lines[line - 1]
            lines[line - 1] = row[: col - 1] + text + row[col - 1 :]
        tabs[name] = Source(src.path, "\n".join(lines), src.tab)
    return Shader(tabs, shader.root)


def _line(shader: Shader, path: str, line: int) -> str | None:
    for src in shader.tabs.values():
        if src.path == path:
            lines = src.text.split("\n")
            return lines[line - 1] if 0 < line <= len(lines) else None
    return None
