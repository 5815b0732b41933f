"""The fix of `uniform-outside-mainimage`: the uniform becomes a parameter of every function that
reads it, and of every function on a call chain from mainImage to one of them; mainImage passes
the uniform itself, each other caller its own new parameter. One fix per uniform and file,
shared by all its findings (they are one rewrite)."""

from __future__ import annotations

import re

from ...frontend import syntax as A
from ...semantics.analysis import program_facts
from ...semantics.model import Symbol
from . import Edit, Fix
from .build import fresh_name, node_text, replace, span_text

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

    from ..engine import LintContext

ENTRY = "mainImage"


def parameter_name(uniform: str) -> str:
    """What the parameter is called: Shadertoy's `iTime` -> `time`, `iChannel0` -> `channel0`;
    a uniform of the shader's own, `lightPos` -> `lightPosValue`."""
    if len(uniform) > 1 and uniform[0] == "i" and uniform[1].isupper():
        return uniform[1].lower() + uniform[2:]
    return uniform + "Value"


def uniform_fix(ctx: LintContext, uniform: Symbol) -> Fix | None:
    """The fix passing `uniform` down from mainImage, or None when it cannot be made in this file
    alone (a function or call elsewhere, one that does not compile, a call through a macro, a
    function no call chain leads to from mainImage but that is called)."""
    model = ctx.model
    if model is None:  # no semantic model: no call graph to follow
        return None
    facts = program_facts(model)
    readers = []
    for d in facts.definitions:
        if d.proto.name == ENTRY:
            continue
        if any(
            type(n) is A.Identifier and model.symbol_of(n) is uniform for n in model.body_nodes(d)
        ):
            readers.append(d)
    needs: list[Any] = []  # definitions that get the parameter, callees first
    sites: list[tuple[Any, A.Call]] = []  # (caller definition, call) passing it
    work = list(readers)
    while work:
        d = work.pop()
        if any(d is n for n in needs):
            continue
        fn = model.symbol_of(d.proto)  # None for a definition that did not check
        if d.loc.path != ctx.path or id(d) in facts.broken or fn is None:
            return None
        needs.append(d)
        for caller, call in facts.call_sites(fn):
            sites.append((caller.definition, call))
            if caller.definition.proto.name != ENTRY:
                work.append(caller.definition)
    if not needs:
        return None
    in_word = any("in" in p.qualifiers for d in facts.definitions for p in d.proto.params)
    texts = [span_text(ctx, d.loc, code=True) or "" for d in needs]
    name = fresh_name(ctx, parameter_name(uniform.name), texts=texts)
    edits: list[Edit] = []
    declared = f"{'in ' if in_word else ''}{uniform.type} {name}"
    protos = [d.proto for d in needs]
    needed = {id(model.symbol_of(p)) for p in protos}
    for decl in model.ast.decls:  # forward declarations of the same functions
        if type(decl) is A.FunctionDeclaration and decl.proto is not None:
            sym = model.symbol_of(decl.proto)
            if sym is not None and id(sym) in needed:
                protos.append(decl.proto)
    for proto in protos:
        edit = _add_item(ctx, proto.params, proto.name_loc, declared)
        if edit is None:
            return None
        edits.append(edit)
    for d in needs:
        for n in model.body_nodes(d):
            if type(n) is A.Identifier and model.symbol_of(n) is uniform:
                if node_text(ctx, n) is None:
                    return None
                edits.append(replace(n, name))
    for caller, call in sites:
        if call.loc.path != ctx.path or node_text(ctx, call) is None:
            return None
        passed = uniform.name if caller.proto.name == ENTRY else name
        edit = _add_item(ctx, call.args, call.callee_loc, passed)
        if edit is None:
            return None
        edits.append(edit)
    names = ", ".join(f"'{d.proto.name}'" for d in reversed(needs))
    return Fix(
        f"pass {uniform.name} from mainImage to {names} as the parameter '{name}'",
        ctx.path,
        tuple(edits),
    )


def _add_item(ctx: LintContext, items: list, name_loc: Any, text: str) -> Edit | None:
    """An edit adding `text` as the last item of a parameter or argument list: after its last
    item, or inside the empty parentheses after `name_loc` (`f()`, `f(void)`)."""
    if items:
        last = items[-1].loc
        if last is None or last.path != ctx.path or last.end_line is None:
            return None
        return Edit(last.end_line, last.end_column, last.end_line, last.end_column, f", {text}")
    if name_loc is None or name_loc.path != ctx.path or name_loc.end_line is None:
        return None
    line, col = name_loc.end_line, name_loc.end_column
    code = ctx.scan.code_lines  # comments blanked: a `(` in a comment is not the list's
    m = re.match(r"\s*\(\s*(void\s*)?\)", code[line - 1][col - 1 :])
    if m is None:
        return None
    start = col + m.group(0).index("(") + 1
    if m.group(1):
        vstart = col + m.group(0).index("void")
        return Edit(line, vstart, line, vstart + 4, text)
    return Edit(line, start, line, start, text, item=True)
