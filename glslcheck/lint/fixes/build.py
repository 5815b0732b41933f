"""What rules use to make their fixes' edits: the source text of a node, an expression put in a
node's place (with the parentheses its new place needs), a local variable declared before a
statement, and a name no declaration of the program uses.

A node's text is read from the file the user wrote, at the node's location: the student's own
spelling, spacing and comments are kept. A node that comes from a macro (its text names a
`#define` of the program) or lies in another file has no text here, and gets no fix.
"""

from __future__ import annotations

import re
from functools import lru_cache

from ...frontend import syntax as A
from ...frontend.printer import POSTFIX, PRECEDENCE, PRIMARY, UNARY
from ...language.builtin_functions import BUILTINS, KEYWORDS, RESERVED_WORDS
from . import Edit

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any

    from ..engine import LintContext

# compiled when a fix is made (not with the lint path's stored patterns: base/regexes.py)
_DEFINE = r"^[ \t]*#[ \t]*define[ \t]+([A-Za-z_]\w*)"
_WORD = r"[A-Za-z_]\w*"
_ATOMS = (A.Identifier, A.FloatLiteral, A.IntLiteral, A.BoolLiteral)
_POSTFIXES = (A.Call, A.Index, A.Field, A.MethodCall, A.Postfix)


def program_texts(ctx: LintContext) -> list[str]:
    """The texts of every file of the linted file's program (its shader's tabs), this one first
    with its comments blanked (a word in a comment names nothing)."""
    texts = ["\n".join(ctx.scan.code_lines)]
    if ctx.shader is not None:
        texts += [s.text for s in ctx.shader.sources() if s.path != ctx.source.path]
    return texts


def _macros(ctx: LintContext) -> frozenset[str]:
    return _defines(tuple(program_texts(ctx)))


@lru_cache(maxsize=8)
def _words(texts: tuple[str, ...]) -> frozenset[str]:
    """Every word of the texts (the names a new name must not take)."""
    return frozenset(w for t in texts for w in re.findall(_WORD, t))


@lru_cache(maxsize=8)
def _defines(texts: tuple[str, ...]) -> frozenset[str]:
    """The names `#define`d in the texts (a fix never rewrites through a macro)."""
    return frozenset(m.group(1) for t in texts for m in re.finditer(_DEFINE, t, re.M))


def span_text(ctx: LintContext, loc: Any, code: bool = False) -> str | None:
    """The text of the file at a location of it (None: another file, or no span); with `code`,
    its comments blanked."""
    if loc is None or loc.path != ctx.path or loc.end_line is None or loc.end_column is None:
        return None
    lines = ctx.scan.code_lines if code else ctx.lines
    if not 1 <= loc.line <= loc.end_line <= len(lines):
        return None
    if loc.line == loc.end_line:
        return lines[loc.line - 1][loc.column - 1 : loc.end_column - 1]
    parts = [lines[loc.line - 1][loc.column - 1 :]]
    parts += lines[loc.line : loc.end_line - 1]
    parts.append(lines[loc.end_line - 1][: loc.end_column - 1])
    return "\n".join(parts)


def node_text(ctx: LintContext, node: Any) -> str | None:
    """The text the user wrote for `node`, or None: in another file, from a macro, or without a
    span."""
    text = span_text(ctx, getattr(node, "loc", None))
    if text is None or not text.strip():
        return None
    macros = _macros(ctx)
    if macros and any(w in macros for w in re.findall(_WORD, text)):
        return None
    return text


def replace(node: Any, text: str) -> Edit:
    """An edit putting `text` where `node` is written."""
    loc = node.loc
    return Edit(loc.line, loc.column, loc.end_line, loc.end_column, text)


def replace_with_name(ctx: LintContext, node: Any, name: str) -> Edit:
    """An edit putting the variable `name` where `node` is written, with the parentheses that
    only grouped it (`(a - b).x` -> `ab.x`, `lenSq((a - b))` -> `lenSq(ab)`; a call's own
    parentheses stay)."""
    loc = node.loc
    if loc.line != loc.end_line:
        return replace(node, name)
    code = ctx.scan.code_lines[loc.line - 1]  # comments blanked: a `(` in one is not code
    start, end = loc.column - 1, loc.end_column - 1
    while True:
        a = len(code[:start].rstrip())
        b = end + len(code[end:]) - len(code[end:].lstrip())
        if a == 0 or b >= len(code) or code[a - 1] != "(" or code[b] != ")":
            break
        before = code[: a - 1].rstrip()
        if before and (before[-1].isalnum() or before[-1] in "_])"):
            break  # the parentheses of a call or a constructor
        start, end = a - 1, b + 1
    return Edit(loc.line, start + 1, loc.line, end + 1, name)


def precedence(node: Any) -> int:
    """How tightly an expression binds (the printer's table)."""
    t = type(node)
    if t in _ATOMS:
        return PRIMARY
    if t in _POSTFIXES:
        return POSTFIX
    if t is A.Unary:
        return UNARY
    if t is A.Binary:
        return PRECEDENCE[node.op]
    if t is A.Ternary:
        return PRECEDENCE["?:"]
    if t is A.Assignment:
        return PRECEDENCE["="]
    return PRECEDENCE[","]


def slot(fn: Any, node: Any) -> int:
    """The least precedence an expression written in `node`'s place needs to mean the same
    operand (left-associative operators: the right operand binds tighter)."""
    parent = fn.parent.get(id(node))
    t = type(parent)
    if t is A.Binary:
        p = PRECEDENCE[parent.op]
        return p if node is parent.left else p + 1
    if t is A.Unary:
        return UNARY
    if t in (A.Index, A.Field, A.MethodCall, A.Postfix):
        return POSTFIX if node is not getattr(parent, "index", None) else 0
    if t is A.Ternary:
        return PRECEDENCE["?:"] + 1 if node is parent.cond else PRECEDENCE["?:"]
    if t is A.Assignment:
        return UNARY if node is parent.target else PRECEDENCE["="]
    if t in (A.Call, A.Declarator, A.Sequence):
        return PRECEDENCE["="]
    return 0


def fit(fn: Any, node: Any, text: str, binds: int) -> str:
    """`text` (an expression binding `binds`) ready to replace `node`: in parentheses when its
    place needs them."""
    return text if binds >= slot(fn, node) else f"({text})"


def operand_text(ctx: LintContext, node: Any, binds: int) -> str | None:
    """The user's text of `node` as an operand of an operator binding `binds` (parenthesised
    when it binds more loosely); None when the node has no text here."""
    text = node_text(ctx, node)
    if text is None:
        return None
    return text if precedence(node) >= binds else f"({text})"


def statement_of(fn: Any, node: Any) -> tuple[Any, Any, bool] | None:
    """(statement, its block, whether the way up leaves a loop's condition, step or a body that
    is not a block) for the statement of a `{ }` block that holds `node`; None at the function's
    top or outside a block."""
    cur = node
    in_loop = False
    while True:
        parent = fn.parent.get(id(cur))
        if parent is None:
            return None
        if type(parent) is A.Compound:
            return cur, parent, in_loop
        if type(parent) in (A.For, A.While, A.DoWhile) and cur is not getattr(parent, "init", None):
            in_loop = True
        cur = parent


def line_indent(ctx: LintContext, line: int) -> str:
    text = ctx.lines[line - 1]
    return text[: len(text) - len(text.lstrip())]


def insert_before(ctx: LintContext, stmt: Any, code: str) -> Edit | None:
    """An edit adding the line `code` before the statement `stmt`, at its indentation and above
    the comment lines right over it (they explain `stmt`); on the statement's own line when code
    precedes it there. None when the statement is not in this file."""
    loc = stmt.loc
    if loc is None or loc.path != ctx.path:
        return None
    text = ctx.lines[loc.line - 1]
    before = text[: loc.column - 1]
    if before.strip():
        return Edit(loc.line, loc.column, loc.line, loc.column, f"{code} ")
    indent = before
    line = loc.line
    kinds = ctx.line_kinds
    while line > 1 and str(kinds[line - 2]) == "comment":
        line -= 1
    if any(c.line < line <= c.end_line for c in ctx.comments):
        line = loc.line  # the lines above end a comment opened after code: not inside it
    return Edit(line, 1, line, 1, f"{indent}{code}\n")


_OP_WORDS = {"+": "Plus", "-": "Minus", "*": "Times", "/": "Over"}
_TYPE_NAMES = frozenset(
    f"{p}{k}{n}" for p in ("", "i", "u", "b") for k in ("vec",) for n in (2, 3, 4)
) | frozenset(("float", "int", "uint", "bool", "mat2", "mat3", "mat4"))
_MAX_PARTS = 4


def _parts(node: Any, out: list[str]) -> None:
    if len(out) >= _MAX_PARTS:
        return
    t = type(node)
    if t is A.Binary:  # the operator's word only between two named operands
        left: list[str] = []
        right: list[str] = []
        _parts(node.left, left)
        _parts(node.right, right)
        if left and right:
            out.extend([*left, _OP_WORDS.get(node.op, ""), *right])
        elif left or right:  # a name and a number: scaled or offset
            out.extend([*left, *right, "Scaled" if node.op in ("*", "/") else "Offset"])
        return
    if t is A.Identifier:
        out.append(node.name)
    elif t is A.Field:
        _parts(node.base, out)
        out.append(node.name)
    elif t is A.Call:
        if node.callee not in _TYPE_NAMES:  # `vec3(n * 0.5 + 0.5)` is named for what it holds
            out.append(node.callee or "value")
        for a in node.args:
            _parts(a, out)
    elif t is A.Unary:
        _parts(node.operand, out)
    elif t is A.Index:
        _parts(node.base, out)


def name_hint(node: Any) -> str:
    """A camelCase name made of what an expression reads: `dot(n, l)` -> `dotNL`,
    `light.center - position` -> `lightCenterMinusPosition` (its first few words)."""
    words: list[str] = []
    _parts(node, words)
    words = [w for w in words if w][:_MAX_PARTS]
    if not words:
        return "value"
    name = words[0][0].lower() + words[0][1:] + "".join(w[0].upper() + w[1:] for w in words[1:])
    name = name.replace("__", "_")
    return name if name[0].isalpha() else "value"


def fresh_name(
    ctx: LintContext,
    hint: str,
    taken: set[str] | frozenset[str] = frozenset(),
    texts: list[str] | None = None,
) -> str:
    """`hint`, or `hint2`, `hint3`, ...: the first that is no keyword, reserved word or built-in
    function and that no word of the program's files uses (with `texts`: no word of those texts
    and no top-level name of the program: a parameter of the functions they are)."""
    if texts is None:
        used = _words(tuple(program_texts(ctx))) | set(taken)
    else:
        used = _words(tuple(texts)) | _top_level_names(ctx.model) | set(taken)
    for n in range(1, 1000):
        name = hint if n == 1 else f"{hint}{n}"
        if (
            name not in used
            and name not in KEYWORDS
            and name not in RESERVED_WORDS
            and name not in BUILTINS
            and not name.startswith("gl_")
            and "__" not in name
        ):
            return name
    return f"{hint}_{len(used)}"


def _top_level_names(model: Any) -> set[str]:
    names: set[str] = set()
    for d in getattr(getattr(model, "ast", None), "decls", ()):
        proto = getattr(d, "proto", None)
        if proto is not None:
            names.add(proto.name)
        for dec in getattr(d, "declarators", ()) or ():
            names.add(dec.name)
        struct = getattr(getattr(d, "type", None), "struct_", None)
        if struct is not None and getattr(struct, "name", None):
            names.add(struct.name)
    return names


def facts_of(ctx: LintContext, node: Any) -> Any:
    """The facts of the function of the linted file that holds `node`, or None."""
    from ...semantics.analysis import program_facts

    for fn in program_facts(ctx.model).in_file(ctx.path):
        if id(node) in fn.enter:
            return fn
    return None


def declare_before(
    ctx: LintContext,
    fn: Any,
    at: Any,
    kind: Any,
    value: str,
    hint: str,
    uses: list[Any] = (),  # type: ignore[assignment]
) -> tuple[str, Edit] | None:
    """A local `kind name = value;` declared before the statement that holds `at`, where every
    node of `uses` can read it (each in that statement's block, not before it): (the name, the
    edit). None when there is no such place: `at` outside a block or in a loop's condition or
    step (computing it once would change it), a use outside the block, or a type without a
    name."""
    found = statement_of(fn, at)
    if found is None or str(kind) in ("ERROR", "void"):
        return None
    stmt, block, in_loop = found
    if in_loop:
        return None
    for u in uses:
        if not fn.contains(block, u) or fn.enter[id(u)] < fn.enter[id(stmt)]:
            return None
    name = fresh_name(ctx, hint)
    insert = insert_before(ctx, stmt, f"{kind} {name} = {value};")
    return None if insert is None else (name, insert)


def local_for(
    ctx: LintContext, fn: Any, first: Any, uses: list[Any], hint: str | None = None
) -> tuple[str, list[Edit]] | None:
    """A local variable holding the value of `first`, declared before the statement of `first`
    and read at `first` and at every node of `uses`: (the name, the edits), or None (see
    `declare_before`; also when a node's text is not the user's)."""
    value = node_text(ctx, first)
    if value is None or any(node_text(ctx, u) is None for u in uses):
        return None
    found = declare_before(
        ctx, fn, first, fn.model.type_of(first), value, hint or name_hint(first), uses
    )
    if found is None:
        return None
    name, insert = found
    return name, [insert] + [replace_with_name(ctx, n, name) for n in [first, *uses]]
