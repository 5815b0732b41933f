"""The directives: `#define #undef #if #ifdef #ifndef #elif #else #endif #error #pragma
#extension #version #line` and the null directive `#`, each checked as GLSL ES 3.00 (section 3.4)
and the drivers (Mesa, ANGLE) check it.
"""

from __future__ import annotations

from ...base.diagnostics import Diagnostic, GlslError
from ...base.regexes import compiled
from .conditions import INTEGER_RE, eval_if
from .context import Conditional, PreprocessorState
from .expansion import expand_list
from .result import Macro
from .tokens import ID, NUM, OP, OTHER, WS, Token, lex, lex_all
from .units import RULE, Unit

_BEHAVIORS = ("require", "enable", "warn", "disable")
_COND = ("if", "ifdef", "ifndef", "elif", "else", "endif")
_INVARIANT_ALL_RE = compiled(r"STDGL[ \t]+invariant[ \t]*\([ \t]*all[ \t]*\)[ \t]*")


def handle_directive(
    pp: PreprocessorState, u: Unit, start: int, hash_pos: int, nl: int, active: bool
) -> None:
    text = u.stripped
    name_tok = lex(text, hash_pos + 1, nl)
    if name_tok is None:
        return  # the null directive
    name = name_tok.text if name_tok.kind == ID else ""
    if not active:
        if not (name in ("elif", "else", "endif") and pp.conds and pp.conds[-1].parent_active):
            pp.mark_inactive(u, start, nl)
        if name in _COND:
            _conditional(pp, name, name_tok, lex_all(text, name_tok.end, nl), hash_pos, nl, active)
        return
    if name in ("error", "pragma"):
        rest = text[name_tok.end : nl].strip(WS)
        loc = u.span(hash_pos, nl)
        if name == "error":
            raise GlslError(Diagnostic(f"#error: {rest}" if rest else "#error", loc, rule=RULE))
        if (pp.version or (300 if pp.shadertoy else 100)) == 300 and _INVARIANT_ALL_RE.fullmatch(
            rest
        ):
            # GLSL ES 3.00 section 4.6.1: only a vertex shader's outputs can be invariant;
            # Mesa: "pragma `invariant(all)' cannot be used in a fragment shader".
            raise GlslError(
                Diagnostic(
                    "#pragma STDGL invariant(all) cannot be used in a fragment shader "
                    "(GLSL ES 3.00 section 4.6.1)",
                    loc,
                    rule=RULE,
                    help="remove it: a fragment shader's outputs are never invariant",
                )
            )
        pp.pragmas.append((rest, loc))
        return
    toks = lex_all(text, name_tok.end, nl)
    for t in toks:
        if t.kind == OTHER:
            raise pp.token_error(f"unexpected character {t.text!r} in a preprocessor directive", t)
    if name in _COND:
        _conditional(pp, name, name_tok, toks, hash_pos, nl, active)
    elif name == "define":
        _define(pp, toks, name_tok)
    elif name == "undef":
        if not toks or toks[0].kind != ID:
            raise pp.token_error("#undef needs a macro name", toks[0] if toks else name_tok)
        _check_name(pp, toks[0], "undefine")
        if len(toks) > 1:
            raise pp.token_error("#undef takes a single macro name", toks[1])
        pp.macros.pop(toks[0].text, None)
    elif name == "extension":
        _extension(pp, toks, name_tok, hash_pos, nl)
    elif name == "version":
        _version(pp, toks, name_tok, hash_pos, nl)
    elif name == "line":
        _line(pp, toks, name_tok, nl)
    else:
        raise pp.token_error(
            f"unknown preprocessor directive '#{name_tok.text}'",
            name_tok,
            help="GLSL ES has #define #undef #if #ifdef #ifndef #elif #else #endif "
            "#error #pragma #extension #version #line",
        )
    pp.seen_code = pp.seen_code or name != "version"


def _check_name(pp: PreprocessorState, t: Token, verb: str) -> None:
    n = t.text
    if n.startswith("GL_"):
        raise pp.token_error(
            f"cannot {verb} '{n}': macro names starting with 'GL_' are reserved", t
        )
    if n == "defined":
        raise pp.token_error(f"cannot {verb} 'defined'", t)
    if n in ("__LINE__", "__FILE__", "__VERSION__"):
        raise pp.token_error(f"cannot {verb} the predefined macro '{n}'", t)
    if "__" in n:
        d = Diagnostic(
            f"macro names containing '__' are reserved: '{n}'",
            pp.unit.span(t.start, t.end),
            severity="warning",
            rule=RULE,
        )
        if pp.version == 100:  # GLSL ES 1.00 makes it an error
            raise GlslError(Diagnostic(d.message, d.loc, rule=RULE))
        pp.diagnostics.append(d)


def _define(pp: PreprocessorState, toks: list[Token], directive: Token) -> None:
    if not toks or toks[0].kind != ID:
        raise pp.token_error("#define needs a macro name", toks[0] if toks else directive)
    nt = toks[0]
    _check_name(pp, nt, "define")
    params: tuple[str, ...] | None = None
    i = 1
    if len(toks) > 1 and toks[1].text == "(" and not toks[1].ws:
        plist: list[str] = []
        i = 2
        while True:
            if i >= len(toks):
                raise pp.token_error(
                    f"the parameter list of macro '{nt.text}' is not closed: a ')' is missing", nt
                )
            t = toks[i]
            if t.text == ")" and not plist:
                i += 1
                break
            if t.kind != ID:
                raise pp.token_error(
                    f"expected a parameter name in macro '{nt.text}', found '{t.text}'", t
                )
            if t.text in plist:
                raise pp.token_error(f"macro '{nt.text}' has two parameters named '{t.text}'", t)
            plist.append(t.text)
            if i + 1 >= len(toks):
                raise pp.token_error(
                    f"the parameter list of macro '{nt.text}' is not closed: a ')' is missing", nt
                )
            sep = toks[i + 1]
            i += 2
            if sep.text == ")":
                break
            if sep.text != ",":
                raise pp.token_error(
                    f"expected ',' or ')' in the parameters of macro '{nt.text}', "
                    f"found '{sep.text}'",
                    sep,
                )
        params = tuple(plist)
    body = toks[i:]
    for t in body:
        if t.text in ("#", "##"):
            raise pp.token_error(
                f"the '{t.text}' operator is not allowed in GLSL ES",
                t,
                help="GLSL ES macros cannot turn arguments into strings or paste tokens",
            )
    new = Macro(
        nt.text, params, tuple(t.text for t in body), pp.unit.span(nt.start, nt.end), False, body
    )
    old = pp.macros.get(nt.text)
    if old is not None and (
        old.params != params
        or old.body != new.body
        or [t.ws for t in old.tokens[1:]] != [t.ws for t in body[1:]]
    ):
        where = f" at {old.loc}" if old.loc else " (it is predefined)"
        raise pp.token_error(
            f"macro '{nt.text}' is already defined{where} with a different body",
            nt,
            help=f"use #undef {nt.text} first to change it",
        )
    pp.macros[nt.text] = new


def _conditional(
    pp: PreprocessorState,
    name: str,
    nt: Token,
    toks: list[Token],
    hash_pos: int,
    nl: int,
    active: bool,
) -> None:
    """#if #ifdef #ifndef #elif #else #endif; `active`: is the group holding this line active?"""
    loc_s, loc_e = hash_pos, nt.end
    if name in ("if", "ifdef", "ifndef"):
        parent = active
        value = False
        if parent:
            if name == "if":
                value = eval_if(pp, toks, nt)
            else:
                if not toks or toks[0].kind != ID:
                    raise pp.token_error(f"#{name} needs a macro name", toks[0] if toks else nt)
                if len(toks) > 1:
                    raise pp.token_error(
                        f"unexpected '{toks[1].text}' after #{name} {toks[0].text}", toks[1]
                    )
                value = (toks[0].text in pp.macros) == (name == "ifdef")
        pp.conds.append(Conditional(pp.unit.span(loc_s, loc_e), parent, value))
        pp.cond_active = value
        return
    if not pp.conds:
        raise pp.error(f"#{name} without a matching #if", loc_s, loc_e)
    c = pp.conds[-1]
    if name == "endif":
        if toks and c.parent_active:
            raise pp.token_error(f"unexpected '{toks[0].text}' after #endif", toks[0])
        pp.conds.pop()
        pp.cond_active = c.parent_active  # back in the enclosing group
        return
    if c.seen_else:
        raise pp.error(f"#{name} after #else", loc_s, loc_e)
    if name == "else":
        if toks and c.parent_active:
            raise pp.token_error(f"unexpected '{toks[0].text}' after #else", toks[0])
        c.seen_else = True
        pp.cond_active = c.parent_active and not c.taken
        c.taken = True
        return
    # elif
    if c.parent_active and not c.taken:
        value = eval_if(pp, toks, nt)
        c.taken = value
        pp.cond_active = value
    else:
        pp.cond_active = False


def _extension(pp: PreprocessorState, toks: list[Token], nt: Token, hash_pos: int, nl: int) -> None:
    # GLSL ES 3.00 3.4: #extension comes before any code. Shadertoy puts its precision and
    # uniform declarations before a tab's text, so in a tab it always comes after code;
    # WebGL 2 (ANGLE) and Mesa reject the program.
    if pp.shadertoy:
        raise pp.error(
            "#extension is not allowed in a Shadertoy tab: Shadertoy's own declarations come "
            "first, and an #extension after code is rejected by WebGL 2",
            hash_pos,
            nl,
        )
    if pp.seen_tokens:
        raise pp.error("#extension must come before any code in the shader", hash_pos, nl)
    shape = [t.kind for t in toks[:3]] == [ID, OP, ID] and toks[1].text == ":"
    if not shape or len(toks) != 3:
        bad = toks[3] if shape else (toks[0] if toks else nt)
        raise pp.token_error("#extension must read '#extension name : behavior'", bad)
    ext, behavior = toks[0].text, toks[2].text
    if behavior not in _BEHAVIORS:
        raise pp.token_error(
            f"unknown #extension behavior '{behavior}': use require, enable, warn or disable",
            toks[2],
        )
    if ext == "all" and behavior in ("require", "enable"):
        raise pp.token_error(
            f"'#extension all' can only be 'warn' or 'disable', not '{behavior}'", toks[2]
        )
    pp.extensions.append((ext, behavior, pp.unit.span(hash_pos, toks[2].end)))


def _version(pp: PreprocessorState, toks: list[Token], nt: Token, hash_pos: int, nl: int) -> None:
    if pp.shadertoy:
        raise pp.error("Shadertoy adds #version 300 es itself; remove this line", hash_pos, nl)
    if pp.version is not None:
        raise pp.error("a second #version line", hash_pos, nl)
    if pp.seen_code or pp.unit.index > 0:
        raise pp.error(
            "#version must be the first line of the shader (only comments may come before it)",
            hash_pos,
            nl,
        )
    words = [t.text for t in toks]
    if words == ["300", "es"]:
        pp.version = 300
    elif words == ["100"]:
        pp.version = 100
    elif words == ["300"]:
        raise pp.error("GLSL ES 3.00 is written '#version 300 es'", hash_pos, nl)
    else:
        raise pp.error(
            f"unsupported version '#version {' '.join(words)}': glslcheck reads GLSL ES 3.00 "
            "('#version 300 es') and 1.00 ('#version 100')",
            hash_pos,
            nl,
        )
    pp.macros["__VERSION__"] = Macro(
        "__VERSION__", None, (str(pp.version),), None, True, [Token(NUM, str(pp.version), 0, 0)]
    )


def _line(pp: PreprocessorState, toks: list[Token], nt: Token, nl: int) -> None:
    expr = expand_list(pp, toks, 0)
    nums = []
    for t in expr:
        # GLSL ES 3.00 section 3.4: "constant integer expressions"; an integer literal in
        # any base (decimal, octal 010, hex 0x10) is one, as Mesa and glslang accept.
        if t.kind != NUM or not INTEGER_RE.fullmatch(t.text):
            raise pp.token_error(
                f"#line takes a line number and an optional source number, not '{t.text}'", t
            )
        nums.append(
            int(t.text, 8) if t.text.startswith("0") and t.text[1:].isdigit() else int(t.text, 0)
        )
    if not 1 <= len(nums) <= 2:
        raise pp.token_error("#line takes a line number and an optional source number", nt)
    next_line = pp.unit.line_of(nl) + 1
    pp.line_delta = nums[0] - next_line
    if len(nums) == 2:
        pp.file_number = nums[1]
