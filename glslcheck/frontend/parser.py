"""Parsing: preprocessed GLSL ES 3.00 text -> tokens -> LALR parse tree -> the typed AST
(frontend/syntax.py).

Owns the loaded parser (once per process, from the tables frontend/parse_tables.py ships beside
grammar/glsl.lark: nothing is built or cached at run time), the pass that builds AST nodes from
the parse tree (one `_build_<rule>` method per grammar rule), and the translation of syntax
errors into messages in words that point into the user's file.

Lark supplies the terminals, the tables and the tree shapes, ahead of time; two small modules
run them faster than Lark's general-purpose loops do, with the same results: frontend/lexer.py (one
master regex over the grammar's terminals, plus the struct-name rule) and frontend/lalr.py (the LALR
loop over the table). tests/parse/test_fast_parser.py checks both against Lark itself.

Entry points: `parse_shader(shader)` for a Shadertoy shader (Common + Image, as Shadertoy
compiles them), `parse_units(sources)` for any list of files, and `parse_string(text)` for tests.
"""

from __future__ import annotations

import gc

from ..base.diagnostics import Diagnostic, GlslError, Location, pending_location, register_source
from ..base.records import field, record
from ..base.recursion import enter_deep, leave_deep

# The keywords (3.6), to tell "a keyword used as a name" in error messages.
# one table, shared with the checker
from ..language.builtin_functions import KEYWORDS  # noqa: E402
from ..language.glsl_types import BY_NAME  # noqa: E402
from ..shadertoy.sources import Shader, Source
from . import parse_tables
from . import syntax as A
from .lalr import Driver, Tree, UnexpectedToken
from .lexer import BadNameError, Lexer, Token, Tokens, UnexpectedCharacters, UnexpectedInput

_NOLOC = A._NOLOC  # a node's location until the builder sets it

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable

_GRAMMAR_CACHE: dict[str, Parser] = {}


def grammar_text() -> str:
    """The grammar, read from the installed package (grammar/ ships as glslcheck.grammar)."""
    return parse_tables.grammar_text()


@record(frozen=True, slots=False)
class Parser:
    """The loaded grammar's tables and what runs them: the lexer (frontend/lexer.py) and the LALR
    driver (frontend/lalr.py), both made from the tables frontend/parse_tables.py ships with the
    grammar."""

    lexer: Lexer
    driver: Driver
    words: dict[str, str]  # what each terminal is called in an error message


def get_parser() -> Parser:
    parser = _GRAMMAR_CACHE.get("parser")
    if parser is None:
        tables = parse_tables.load()
        parser = Parser(Lexer(tables["lexer"]), Driver(tables["parser"]), tables["words"])
        _GRAMMAR_CACHE["parser"] = parser
    return parser


def parse_tree(text: str) -> Tree:
    """The parse tree of preprocessed text; raises UnexpectedInput or BadNameError."""
    parser = get_parser()
    return parser.driver.parse(parser.lexer.tokenize(text))


@record(slots=False)
class ParseResult:
    """The AST of a program and what the preprocessor learned on the way."""

    ast: A.TranslationUnit
    pp: object  # preprocess.PPResult: text, locate, comments, macros, version, extensions
    sources: list[Source] = field(default_factory=list)


# ---------------------------------------------------------------------------------------------
# Entry points
# ---------------------------------------------------------------------------------------------


def parse_units(units: list[Source], *, shadertoy: bool = True) -> ParseResult:
    """Preprocess and parse files compiled together (Common then Image)."""
    from .preprocess import preprocess

    for u in units:
        register_source(u.path, u.text)
    plain = any(u.is_plain_glsl for u in units)
    pp = preprocess(units, shadertoy=shadertoy and not plain)
    tree = _parse_text(pp.text, pp.locate_span)
    return ParseResult(tree, pp, list(units))


def parse_shader(shader: Shader, tab: str = "Image") -> ParseResult:
    """Parse one pass of a Shadertoy shader as Shadertoy compiles it (Common + the tab)."""
    return parse_units(shader.units_for(tab))


def parse_string(text: str, path: str = "<string>") -> A.TranslationUnit:
    """Parse GLSL text (preprocessed as a Shadertoy Image tab); raises GlslError."""
    return parse_units([Source(path, text)]).ast


def _parse_text(text: str, locate_span: Callable[[int, int], Location]) -> A.TranslationUnit:
    # The parse builds hundreds of thousands of small acyclic objects (tokens, trees, nodes);
    # the cyclic garbage collector rescanning them made a 10,000-function file quadratic.
    gc_was_enabled = gc.isenabled()
    gc.disable()
    try:
        return _parse_text_no_gc(text, locate_span)
    finally:
        if gc_was_enabled:
            gc.enable()


def _parse_text_no_gc(text: str, locate_span: Callable[[int, int], Location]) -> A.TranslationUnit:
    parser = get_parser()
    lexed = parser.lexer.tokenize(text)
    try:
        tree = parser.driver.parse(lexed)
    except BadNameError as e:  # a reserved word or an over-long identifier
        start, end = e.token.start_pos, e.token.end_pos
        assert start is not None and end is not None  # a token the lexer made
        raise GlslError(Diagnostic(e.message, locate_span(start, end), help=e.help)) from None
    except UnexpectedInput as e:
        raise GlslError(_syntax_error(e, lexed, locate_span)) from None
    builder = _Builder(locate_span, text)
    # Deeply nested expressions (hundreds of levels) recurse in the builder: allow it.
    enter_deep()
    try:
        return builder.build(tree)
    except RecursionError:
        raise GlslError(
            Diagnostic("the program is nested too deeply to analyse", locate_span(0, 0))
        ) from None
    finally:
        leave_deep()


# ---------------------------------------------------------------------------------------------
# Syntax errors in words
# ---------------------------------------------------------------------------------------------


_EXPRESSION_START = {
    "IDENTIFIER",
    "INTCONSTANT",
    "FLOATCONSTANT",
    "LPAR",
    "MINUS",
    "BANG",
    "TILDE",
    "TRUE",
    "FALSE",
}
_DECL_WORDS = {
    "const",
    "uniform",
    "in",
    "out",
    "inout",
    *A.PRECISION_QUALIFIERS,
    "flat",
    "smooth",
    "invariant",
    "layout",
    "centroid",
    "struct",
    "precision",
}


def _what_statement(history: list[Token]) -> str:
    """Name the construct that the last tokens belong to: declaration, return statement, ..."""
    start = len(history)
    depth = 0
    while start > 0:
        tok = history[start - 1]
        if tok.value in (")", "]", "}"):
            depth += 1
        elif tok.value in ("(", "[", "{"):
            if depth == 0:
                break
            depth -= 1
        elif depth == 0 and tok.value == ";":
            break
        start -= 1
    if start >= len(history):
        return "statement"
    first = history[start]
    if first.type == "TYPE_NAME" or first.value in _DECL_WORDS or first.value in _BASIC_TYPES:
        # `vec3 p = ...` or `vec3(1.0);`: a declaration unless a '(' follows the type.
        if len(history) > start + 1 and history[start + 1].value == "(":
            return "expression"
        return "declaration"
    if first.value == "return":
        return "return statement"
    return "statement"


_BASIC_TYPES = frozenset(BY_NAME)  # every built-in type name, from the one type table


def _innermost_open(brackets: list[Token], tok: Token) -> Token | None:
    """The innermost bracket still open before `tok` (which may itself have been pushed)."""
    if brackets and brackets[-1] is tok:
        return brackets[-2] if len(brackets) >= 2 else None
    return brackets[-1] if brackets else None


def _describe(tok: Token) -> str:
    return "the end of the file" if tok.type == "$END" else f"'{tok.value}'"


def _syntax_error(e: UnexpectedInput, lexed: Tokens, locate_span) -> Diagnostic:
    words = get_parser().words
    text = lexed.text
    # What the parser had seen: the tokens up to the one it failed on (all of them at the end
    # of the file or at a lexer error).
    seen = lexed.count_through(e.token) if isinstance(e, UnexpectedToken) else len(lexed.tokens)
    history = lexed.history(seen)
    open_brackets = lexed.open_brackets(seen)
    if isinstance(e, UnexpectedCharacters):
        pos = e.pos_in_stream
        ch = text[pos] if pos < len(text) else ""
        loc = locate_span(pos, pos + 1)
        if ch == "\x00":
            return Diagnostic("unexpected NUL byte; is this a binary file?", loc)
        if ord(ch or " ") > 127:
            return Diagnostic(
                f"unexpected character '{ch}': GLSL source is ASCII outside comments",
                loc,
                help="names may use only the letters a-z and A-Z, digits and '_'",
            )
        if ch in "\"'":
            return Diagnostic(f"unexpected {ch}: GLSL has no string or character literals", loc)
        if ch == "#":
            return Diagnostic("a '#' directive must start its own line", loc)
        return Diagnostic(f"unexpected character '{ch}'", loc)
    assert isinstance(e, UnexpectedToken)
    tok: Token = e.token
    expected = set(e.expected)
    at_end = tok.type == "$END"
    if history and history[-1] is tok:
        prev = history[-2] if len(history) >= 2 else None
    else:
        prev = history[-1] if history else None
    if at_end:
        end = len(text.rstrip())
        end_loc = locate_span(max(end - 1, 0), max(end, 1))
        if open_brackets:
            last_open = open_brackets[-1]
            closer = {"{": "}", "(": ")", "[": "]"}[last_open.value]
            what = {"{": "block", "(": "parenthesis", "[": "bracket"}[last_open.value]
            return Diagnostic(
                f"this '{last_open.value}' is never closed: the file ends before its '{closer}'",
                locate_span(last_open.start_pos, last_open.end_pos),
                help=f"add the missing '{closer}' where the {what} should end",
            )
        if "SEMICOLON" in expected and prev is not None:
            prev_end = prev.end_pos
            assert prev_end is not None  # a token the lexer made
            return Diagnostic(
                f"expected ';' after this {_what_statement(history)}",
                locate_span(prev_end, prev_end + 1) if prev_end < len(text) else end_loc,
            )
        return Diagnostic("unexpected end of file", end_loc)
    loc = locate_span(tok.start_pos, tok.end_pos)
    if tok.value == "else":
        return Diagnostic(
            "'else' without a matching 'if'",
            loc,
            help="an 'else' must follow the statement of an 'if'; check for a stray ';' or a "
            "missing '{'",
        )
    if tok.type == "IDENTIFIER" and prev is not None and prev.type == "IDENTIFIER":
        return Diagnostic(
            f"unexpected name '{tok.value}' after '{prev.value}'",
            loc,
            help=f"'{prev.value}' is not a type here; declare a struct named '{prev.value}' "
            "before using it, or add an operator",
        )
    if (
        (tok.type == "TYPE_NAME" or tok.value in _BASIC_TYPES or tok.value in KEYWORDS)
        and "IDENTIFIER" in expected
        and prev is not None
        and (prev.value in _BASIC_TYPES or prev.type == "TYPE_NAME" or prev.value == "struct")
    ):
        return Diagnostic(f"'{tok.value}' is a keyword and cannot be used as a name", loc)
    opener = _innermost_open(open_brackets, tok)
    if opener is not None and opener.value in "([":
        closer = ")" if opener.value == "(" else "]"
        if ("RPAR" if closer == ")" else "RSQB") in expected and tok.value in ("{", ";", "}"):
            oloc = locate_span(opener.start_pos, opener.end_pos)
            return Diagnostic(
                f"expected '{closer}' before {_describe(tok)}",
                loc,
                notes=[Diagnostic(f"to match this '{opener.value}'", oloc, severity="note")],
            )
    if (
        "SEMICOLON" in expected
        and prev is not None
        and tok.value not in (",",)
        and prev.value not in (";", "{")
    ):
        # As compilers do: point just past the previous token, where the ';' belongs.
        what = _what_statement(history[:-1] if history and history[-1] is tok else history)
        prev_end = prev.end_pos
        assert prev_end is not None  # a token the lexer made
        ploc = locate_span(prev_end - 1, prev_end)
        ploc = Location(ploc.path, ploc.end_line or ploc.line, ploc.end_column or ploc.column + 1)
        return Diagnostic(
            f"expected ';' after this {what}", ploc, help=f"found {_describe(tok)} instead"
        )
    if tok.value == "}" and prev is not None and prev.value in ("(", ",", "=", "+", "-", "*", "/"):
        return Diagnostic("expected an expression before '}'", loc)
    if expected and len(expected & _EXPRESSION_START) >= 3:
        return Diagnostic(f"expected an expression, found {_describe(tok)}", loc)
    names = sorted({words.get(x, x.lower()) for x in expected})
    if tok.type in ("TYPE_NAME",) or tok.value in _BASIC_TYPES:
        if "IDENTIFIER" in expected:
            return Diagnostic(
                f"'{tok.value}' is a type name and cannot be used as a name here", loc
            )
    if 0 < len(names) <= 4:
        listed = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]
        return Diagnostic(f"expected {listed}, found {_describe(tok)}", loc)
    return Diagnostic(f"unexpected {_describe(tok)}", loc)


# ---------------------------------------------------------------------------------------------
# Parse tree -> AST
# ---------------------------------------------------------------------------------------------


# Rules written with `!` in the grammar: their keyword and operator tokens are their value.
_KEEP_TOKENS = frozenset(
    """parameter_qualifier storage_qualifier interpolation_qualifier invariant_qualifier
    precision_qualifier basic_type assign_op bool_literal binary prefix unary index method_call
    field postfix""".split()
)
# Tokens that carry a value in every rule.
_VALUE_TOKENS = frozenset({"IDENTIFIER", "TYPE_NAME", "INTCONSTANT", "FLOATCONSTANT"})


class _Builder:
    """Builds AST nodes: `_build_<rule>` for each grammar rule (or alias) of grammar/glsl.lark.

    The most frequent nodes are made with their fields in order, without keywords (a class
    call with keyword arguments builds a dict of them); each keeps the order the keywords had,
    so children are built in the same order."""

    def __init__(self, locate_span: Callable[[int, int], Location], text: str) -> None:
        self.locate_span = locate_span
        self.text = text
        self._spans: dict = {}

    def build(self, tree: Tree) -> A.TranslationUnit:
        decls = [self.node(c) for c in tree.children if c is not None]
        unit = A.TranslationUnit(decls=decls)
        if decls:
            unit.loc = decls[0].loc.span_to(decls[-1].loc)
        else:
            unit.loc = self.locate_span(0, 0)
        return unit

    # -- helpers ------------------------------------------------------------------------------
    def loc(self, item: Tree | Token) -> Location:
        """The span from the first to the last token of a subtree (lalr.Driver sets a tree's
        `start_pos` and `end_pos` as a token has them)."""
        start, end = item.start_pos, item.end_pos
        if start is None:  # a tree without tokens
            return self.locate_span(0, 0)
        assert end is not None  # a start means a first token, so a last one
        # Nested nodes often share both ends (a declaration and its type, a call and its
        # callee): one location for each span, computed when it is first read (a lint reads
        # about a third of them).
        key = (start, end)
        loc = self._spans.get(key)
        if loc is None:
            loc = self._spans[key] = pending_location(self.locate_span, start, end)
        return loc

    def node(self, item):
        if item is None:
            return None
        if type(item) is Token:
            raise AssertionError(f"unexpected token {item!r}")
        data = item.data
        children = item.children
        if data not in _KEEP_TOKENS:
            # Punctuation and keywords matter only for the span; the rule says the rest.
            children = [c for c in children if type(c) is not Token or c.type in _VALUE_TOKENS]
        result = _BUILDERS[data](self, item, children)
        if result is not None and result.loc is _NOLOC:
            result.loc = self.loc(item)
        return result

    def error(self, message: str, item, help: str | None = None):
        raise GlslError(Diagnostic(message, self.loc(item), help=help))

    @staticmethod
    def trees(children) -> list[Tree]:
        return [c for c in children if isinstance(c, Tree)]

    # -- external declarations -----------------------------------------------------------------
    def _build_function_definition(self, t, c):
        return A.FunctionDefinition(self.node(c[0]), self.node(c[1]))

    def _build_function_prototype(self, t, c):
        fst, name, params = c
        params = params if isinstance(params, Tree) else None
        qualifiers, rtype = self._fully_specified(fst)
        return A.FunctionPrototype(
            qualifiers=qualifiers,
            return_type=rtype,
            name=str(name),
            params=[self.node(p) for p in self.trees(params.children)]
            if params is not None
            else [],
            name_loc=self.loc(name),
        )

    def _build_parameter_declaration(self, t, c):
        quals = [q for q in c if isinstance(q, Tree) and q.data == "parameter_qualifier"]
        rest = [x for x in c if not (isinstance(x, Tree) and x.data == "parameter_qualifier")]
        tspec, name, *arrays = rest
        array = self._one_array(arrays)
        words = []
        for q in quals:
            tok = q.children[0]
            words.append(str(tok.children[0]) if isinstance(tok, Tree) else str(tok))
        return A.Param(
            qualifiers=words,
            type=self.node(tspec),
            name=str(name) if name is not None else None,
            array=array,
            name_loc=self.loc(name) if name is not None else self.loc(t),
        )

    def _build_function_declaration(self, t, c):
        return A.FunctionDeclaration(proto=self.node(c[0]))

    def _fully_specified(self, fst: Tree):
        tq, tspec = fst.children
        return (self._qualifiers(tq) if tq is not None else None), self.node(tspec)

    def _build_variable_declaration(self, t, c):
        qualifiers, tspec = self._fully_specified(c[0])
        decls = [self.node(d) for d in c[1:] if d is not None]
        return A.VariableDeclaration(qualifiers, tspec, decls)

    def _build_declarator(self, t, c):
        name, *arrays, init = c
        return A.Declarator(str(name), self._one_array(arrays), self.node(init), self.loc(name))

    def _build_precision_declaration(self, t, c):
        return A.PrecisionDeclaration(precision=str(c[0].children[0]), type=self.node(c[1]))

    def _build_block_declaration(self, t, c):
        quals = self._qualifiers(c[0])
        name = c[1]
        members = [self.node(m) for m in c[2:] if isinstance(m, Tree) and m.data == "struct_member"]
        tail = [x for x in c[2:] if not (isinstance(x, Tree) and x.data == "struct_member")]
        inst, array = tail if len(tail) == 2 else (None, None)
        return A.BlockDeclaration(
            qualifiers=quals,
            block_name=str(name),
            members=members,
            instance=str(inst) if inst is not None else None,
            array=self.node(array),
        )

    def _build_invariant_declaration(self, t, c):
        return A.InvariantDeclaration(
            qualifiers=self._qualifiers(c[0]), names=[str(x) for x in c[1:]]
        )

    def _build_qualifier_declaration(self, t, c):
        return A.QualifierDeclaration(qualifiers=self._qualifiers(c[0]))

    def _qualifiers(self, tq: Tree) -> A.Qualifiers:
        words: list[str] = []
        layouts: list[A.Layout] = []
        for q in tq.children:
            if q.data == "layout_qualifier":
                layouts.append(self.node(q))
                words.append("layout")
            else:
                words.append(" ".join(str(x) for x in q.children))
        node = A.Qualifiers(words=words, layouts=layouts)
        node.loc = self.loc(tq)
        return node

    def _build_layout_qualifier(self, t, c):
        return A.Layout(ids=[self.node(x) for x in c])

    def _build_layout_id(self, t, c):
        name, value = c[0], c[-1]
        return A.LayoutId(
            name=str(name), value=self._int_value(value)[0] if value is not None else None
        )

    def _build_layout_shared(self, t, c):
        return A.LayoutId(name="shared")

    # -- types ----------------------------------------------------------------------------------
    def _build_type_specifier(self, t, c):
        spec = self._nonarray(c[0])
        spec.array = self._one_array(c[1:])
        spec.loc = self.loc(t)
        return spec

    def _nonarray(self, item: Tree) -> A.TypeSpec:
        if item.data == "basic_type":
            spec = A.TypeSpec(str(item.children[0]))  # (name)
        elif item.data == "type_name":
            spec = A.TypeSpec(name=str(item.children[0]), is_struct_name=True)
        else:
            spec = A.TypeSpec(struct_=self.node(item))
        spec.loc = self.loc(item)
        return spec

    def _one_array(self, arrays: list) -> A.ArraySpec | None:
        """GLSL ES 3.00 arrays have one dimension (4.1.9): a second `[]` is an error."""
        arrays = [a for a in arrays if a is not None]
        if len(arrays) > 1:
            self.error(
                "arrays of arrays are not allowed in GLSL ES 3.00: an array has one dimension",
                arrays[1],
                help="use a one-dimensional array and index it as [i * columns + j]",
            )
        return self.node(arrays[0]) if arrays else None

    def _build_array_specifier(self, t, c):
        return A.ArraySpec(size=self.node(c[0]))

    def _build_struct_specifier(self, t, c):
        name = c[0]
        return A.StructSpec(
            name=str(name) if name is not None else None, members=[self.node(m) for m in c[1:]]
        )

    def _build_struct_member(self, t, c):
        tq, tspec, *decls = c
        return A.StructMember(
            qualifiers=self._qualifiers(tq) if tq is not None else None,
            type=self.node(tspec),
            declarators=[self.node(d) for d in decls],
        )

    def _build_struct_declarator(self, t, c):
        return A.StructDeclarator(name=str(c[0]), array=self._one_array(c[1:]))

    # -- statements ----------------------------------------------------------------------------
    def _build_compound_statement(self, t, c):
        return A.Compound([self.node(s) for s in c])

    def _build_declaration_statement(self, t, c):
        return A.DeclarationStatement(self.node(c[0]))

    def _build_expression_statement(self, t, c):
        return A.ExpressionStatement(self.node(c[0]))

    def _build_if_statement(self, t, c):
        return A.If(cond=self.node(c[0]), then=self.node(c[1]))

    def _build_if_else_statement(self, t, c):
        return A.If(cond=self.node(c[0]), then=self.node(c[1]), else_=self.node(c[2]))

    def _build_switch_statement(self, t, c):
        return A.Switch(expr=self.node(c[0]), body=[self.node(s) for s in c[1:]])

    def _build_case_label(self, t, c):
        return A.Case(expr=self.node(c[0]))

    def _build_default_label(self, t, c):
        return A.Case(expr=None)

    def _build_while_statement(self, t, c):
        return A.While(cond=self.node(c[0]), body=self.node(c[1]))

    def _build_do_while_statement(self, t, c):
        return A.DoWhile(body=self.node(c[0]), cond=self.node(c[1]))

    def _build_for_statement(self, t, c):
        init, cond, step, body = c
        return A.For(
            init=self.node(init), cond=self.node(cond), step=self.node(step), body=self.node(body)
        )

    def _build_condition_declaration(self, t, c):
        fst, name, init = c
        qualifiers, tspec = self._fully_specified(fst)
        return A.ConditionDeclaration(
            qualifiers=qualifiers,
            type=tspec,
            name=str(name),
            init=self.node(init),
            name_loc=self.loc(name),
        )

    def _build_continue_statement(self, t, c):
        return A.Continue()

    def _build_break_statement(self, t, c):
        return A.Break()

    def _build_return_statement(self, t, c):
        return A.Return(self.node(c[0]))

    def _build_discard_statement(self, t, c):
        return A.Discard()

    # -- expressions ---------------------------------------------------------------------------
    def _build_sequence(self, t, c):
        left = self.node(c[0])
        exprs = left.exprs if isinstance(left, A.Sequence) else [left]
        return A.Sequence(exprs=[*exprs, self.node(c[1])])

    def _build_assignment(self, t, c):
        return A.Assignment(
            str(c[1].children[0]), self.node(c[0]), self.node(c[2])
        )  # (op, target, value)

    def _build_ternary(self, t, c):
        return A.Ternary(cond=self.node(c[0]), then=self.node(c[1]), else_=self.node(c[2]))

    def _build_binary(self, t, c):
        return A.Binary(str(c[1]), self.node(c[0]), self.node(c[2]))  # (op, left, right)

    def _build_prefix(self, t, c):
        return A.Unary(str(c[0]), self.node(c[1]))  # (op, operand)

    _build_unary = _build_prefix

    def _build_postfix(self, t, c):
        return A.Postfix(op=str(c[1]), operand=self.node(c[0]))

    def _build_index(self, t, c):
        trees = [x for x in c if not isinstance(x, Token)]
        return A.Index(base=self.node(trees[0]), index=self.node(trees[1]))

    def _build_field(self, t, c):
        base, _dot, name = c
        return A.Field(self.node(base), str(name), self.loc(name))  # (base, name, name_loc)

    def _build_method_call(self, t, c):
        base, _dot, name = c[0], c[1], c[2]
        return A.MethodCall(base=self.node(base), name=str(name))

    def _build_function_call(self, t, c):
        callee, args = c
        if args is None or args.data == "void_arguments":
            arg_nodes = []
        else:
            arg_nodes = [self.node(a) for a in self.trees(args.children)]
        # (callee, struct_, array, args, constructor, callee_loc): set below
        call = A.Call("", None, None, arg_nodes, False, self.loc(callee))
        kind = callee.data
        if kind == "callee_name":
            call.callee = str(callee.children[0])
        elif kind == "callee_type":
            call.callee = str(callee.children[0].children[0])
            call.constructor = True
        elif kind == "callee_type_name":
            call.callee = str(callee.children[0])
            call.constructor = True
        else:  # callee_array: `float[3](...)`
            spec = self._nonarray(callee.children[0])
            call.callee = spec.name or ""
            call.struct_ = spec.struct_
            call.array = self.node(callee.children[1])
            call.constructor = True
        return call

    def _build_primary_expression(self, t, c):
        # `( expression )`: the parentheses leave no node behind.
        return self.node(c[0])

    def _build_identifier(self, t, c):
        return A.Identifier(str(c[0]))

    def _int_value(self, tok: Token) -> tuple[int, bool]:
        text = str(tok)
        unsigned = text[-1] in "uU"
        digits = text[:-1] if unsigned else text
        if digits[:2] in ("0x", "0X"):
            value = int(digits[2:], 16)
        elif len(digits) > 1 and digits[0] == "0":
            if any(ch in "89" for ch in digits):
                self.error(
                    f"'{text}' is not a valid octal number (a leading 0 means octal)",
                    tok,
                    help=f"write {int(digits)} without the leading zero",
                )
            value = int(digits, 8)
        else:
            value = int(digits)
        if value > 0xFFFFFFFF:
            self.error(f"the integer literal '{text}' does not fit in 32 bits", tok)
        if not unsigned and value > 0x7FFFFFFF:
            value -= 1 << 32  # GLSL ES 3.00 4.1.3: the 32-bit pattern, read as a signed int
        return value, unsigned

    def _build_int_literal(self, t, c):
        value, unsigned = self._int_value(c[0])
        return A.IntLiteral(value, unsigned, str(c[0]))

    def _build_float_literal(self, t, c):
        text = str(c[0])
        return A.FloatLiteral(float(text.rstrip("fF")), text)  # (value, text)

    def _build_bool_literal(self, t, c):
        return A.BoolLiteral(value=str(c[0]) == "true")


# `_build_<rule>` by rule name, for the builder's dispatch.
_BUILDERS = {
    name[len("_build_") :]: f for name, f in vars(_Builder).items() if name.startswith("_build_")
}
