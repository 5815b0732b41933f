"""The GLSL printer: AST -> GLSL ES 3.00 source (`glslcheck parse --print`).

Many tiny methods, one per node class and role (`_stmt_If`, `_expr_Binary`, ...), dispatched
by ast.NodeVisitor. Parentheses come from one precedence table (GLSL ES 3.00
section 5.1), the same ladder grammar/glsl.lark encodes; tests/parse/test_printer.py checks
that the two agree for every pair of binary operators. Printing then parsing gives back the
same tree (`ast.dump` equal), which the corpus round-trip test checks.
"""

from __future__ import annotations

from . import syntax as A

# Higher binds tighter (GLSL ES 3.00 5.1, numbered from the comma operator up).
PRECEDENCE = {
    ",": 1,
    "=": 2,
    "+=": 2,
    "-=": 2,
    "*=": 2,
    "/=": 2,
    "%=": 2,
    "<<=": 2,
    ">>=": 2,
    "&=": 2,
    "^=": 2,
    "|=": 2,
    "?:": 3,
    "||": 4,
    "^^": 5,
    "&&": 6,
    "|": 7,
    "^": 8,
    "&": 9,
    "==": 10,
    "!=": 10,
    "<": 11,
    ">": 11,
    "<=": 11,
    ">=": 11,
    "<<": 12,
    ">>": 12,
    "+": 13,
    "-": 13,
    "*": 14,
    "/": 14,
    "%": 14,
}
UNARY = 15
POSTFIX = 16
PRIMARY = 17


def to_glsl(node: A.Node, indent: str = "    ") -> str:
    """GLSL source for a tree (a TranslationUnit, a statement or an expression)."""
    return _Printer(indent).print(node)


class _Printer(A.NodeVisitor):
    """`_print_<Node>` for a whole program, `_decl_<Node>` for declarations (text without the
    `;`), `_stmt_<Node>` for statements (their lines at an indent level) and `_expr_<Node>`
    for expressions (text and precedence), each dispatched by ast.NodeVisitor."""

    def __init__(self, indent: str) -> None:
        self.unit = indent

    def print(self, node: A.Node) -> str:
        if isinstance(node, A.Expr):
            return self.expr(node)
        if isinstance(node, A.Stmt):
            return "\n".join(self.stmt(node, 0)) + "\n"
        return self.dispatch("_print_", node)

    def missing(self, prefix: str, node: A.Node):
        raise TypeError(f"cannot print {type(node).__name__}")

    # -- program -------------------------------------------------------------------------------
    def _print_TranslationUnit(self, n: A.TranslationUnit) -> str:
        out: list[str] = []
        for d in n.decls:
            if isinstance(d, A.FunctionDefinition):
                if out and out[-1] != "":
                    out.append("")
                out.append(self.prototype(d.proto))
                out.extend(self.stmt(d.body, 0))
                out.append("")
            else:
                out.append(self.declaration(d, 0) + ";")
        return "\n".join(out).rstrip("\n") + "\n"

    # -- declarations --------------------------------------------------------------------------
    def prototype(self, p: A.FunctionPrototype) -> str:
        params = ", ".join(self.param(x) for x in p.params)
        q = self.qualifiers(p.qualifiers)
        return f"{q}{self.type(p.return_type)} {p.name}({params})"

    def param(self, p: A.Param) -> str:
        parts = [*p.qualifiers, self.type(p.type)]
        if p.name is not None:
            parts.append(p.name + self.array(p.array))
        return " ".join(parts)

    def qualifiers(self, q: A.Qualifiers | None) -> str:
        if q is None:
            return ""
        words = []
        layouts = iter(q.layouts)
        for w in q.words:
            if w == "layout":
                lay = next(layouts)
                ids = ", ".join(
                    i.name if i.value is None else f"{i.name} = {i.value}" for i in lay.ids
                )
                words.append(f"layout({ids})")
            else:
                words.append(w)
        return " ".join(words) + (" " if words else "")

    def type(self, t: A.TypeSpec) -> str:
        if t.struct_ is not None:
            base = self.struct(t.struct_)
        else:
            base = t.name or ""
        return base + self.array(t.array)

    def struct(self, s: A.StructSpec, level: int = 0) -> str:
        pad = self.unit * (level + 1)
        members = "".join(f"\n{pad}{self.member(m)};" for m in s.members)
        name = f" {s.name}" if s.name else ""
        return f"struct{name} {{{members}\n{self.unit * level}}}"

    def member(self, m: A.StructMember) -> str:
        decls = ", ".join(d.name + self.array(d.array) for d in m.declarators)
        return f"{self.qualifiers(m.qualifiers)}{self.type(m.type)} {decls}"

    def array(self, a: A.ArraySpec | None) -> str:
        if a is None:
            return ""
        return f"[{self.expr(a.size) if a.size is not None else ''}]"

    def declaration(self, d: A.Node, level: int) -> str:
        return self.dispatch("_decl_", d, level)

    def _decl_VariableDeclaration(self, d: A.VariableDeclaration, level: int) -> str:
        decls = ", ".join(self.declarator(x) for x in d.declarators)
        head = f"{self.qualifiers(d.qualifiers)}{self.type(d.type)}"
        return f"{head} {decls}" if decls else head

    def _decl_FunctionDeclaration(self, d: A.FunctionDeclaration, level: int) -> str:
        return self.prototype(d.proto)

    def _decl_PrecisionDeclaration(self, d: A.PrecisionDeclaration, level: int) -> str:
        return f"precision {d.precision} {self.type(d.type)}"

    def _decl_BlockDeclaration(self, d: A.BlockDeclaration, level: int) -> str:
        pad = self.unit * (level + 1)
        members = "".join(f"\n{pad}{self.member(m)};" for m in d.members)
        inst = f" {d.instance}{self.array(d.array)}" if d.instance else ""
        return (
            f"{self.qualifiers(d.qualifiers)}{d.block_name} "
            f"{{{members}\n{self.unit * level}}}{inst}"
        )

    def _decl_InvariantDeclaration(self, d: A.InvariantDeclaration, level: int) -> str:
        return f"{self.qualifiers(d.qualifiers)}{', '.join(d.names)}"

    def _decl_QualifierDeclaration(self, d: A.QualifierDeclaration, level: int) -> str:
        return self.qualifiers(d.qualifiers).rstrip()

    def declarator(self, d: A.Declarator) -> str:
        text = d.name + self.array(d.array)
        if d.init is not None:
            text += " = " + self.expr(d.init, PRECEDENCE["="])
        return text

    # -- statements ----------------------------------------------------------------------------
    def stmt(self, s: A.Node, level: int) -> list[str]:
        return self.dispatch("_stmt_", s, level)

    def _stmt_Compound(self, s: A.Compound, level: int) -> list[str]:
        pad = self.unit * level
        lines = [pad + "{"]
        for x in s.stmts:
            lines.extend(self.stmt(x, level + 1))
        lines.append(pad + "}")
        return lines

    def _stmt_DeclarationStatement(self, s: A.DeclarationStatement, level: int) -> list[str]:
        return [self.unit * level + self.declaration(s.decl, level) + ";"]

    def _stmt_ExpressionStatement(self, s: A.ExpressionStatement, level: int) -> list[str]:
        return [self.unit * level + (self.expr(s.expr) if s.expr is not None else "") + ";"]

    def _stmt_If(self, s: A.If, level: int) -> list[str]:
        pad = self.unit * level
        lines = [f"{pad}if ({self.expr(s.cond)})"]
        lines.extend(self.body(s.then, level, dangling=s.else_ is not None))
        if s.else_ is not None:
            if isinstance(s.else_, A.If):
                inner = self.stmt(s.else_, level)
                lines.append(f"{pad}else {inner[0].lstrip()}")
                lines.extend(inner[1:])
            else:
                lines.append(pad + "else")
                lines.extend(self.body(s.else_, level))
        return lines

    def _stmt_Switch(self, s: A.Switch, level: int) -> list[str]:
        pad = self.unit * level
        lines = [f"{pad}switch ({self.expr(s.expr)})", pad + "{"]
        for x in s.body:
            lines.extend(self.stmt(x, level + (0 if isinstance(x, A.Case) else 1)))
        lines.append(pad + "}")
        return lines

    def _stmt_Case(self, s: A.Case, level: int) -> list[str]:
        pad = self.unit * level
        return [f"{pad}case {self.expr(s.expr)}:" if s.expr is not None else f"{pad}default:"]

    def _stmt_While(self, s: A.While, level: int) -> list[str]:
        return [f"{self.unit * level}while ({self.condition(s.cond)})", *self.body(s.body, level)]

    def _stmt_DoWhile(self, s: A.DoWhile, level: int) -> list[str]:
        pad = self.unit * level
        return [f"{pad}do", *self.body(s.body, level), f"{pad}while ({self.expr(s.cond)});"]

    def _stmt_For(self, s: A.For, level: int) -> list[str]:
        init = self.stmt(s.init, 0)[0] if s.init is not None else ";"
        cond = self.condition(s.cond) if s.cond is not None else ""
        step = self.expr(s.step) if s.step is not None else ""
        head = f"{self.unit * level}for ({init} {cond}; {step})".replace("( ", "(").replace(
            " ;", ";"
        )
        return [head, *self.body(s.body, level)]

    def _stmt_Break(self, s: A.Break, level: int) -> list[str]:
        return [self.unit * level + "break;"]

    def _stmt_Continue(self, s: A.Continue, level: int) -> list[str]:
        return [self.unit * level + "continue;"]

    def _stmt_Discard(self, s: A.Discard, level: int) -> list[str]:
        return [self.unit * level + "discard;"]

    def _stmt_Return(self, s: A.Return, level: int) -> list[str]:
        return [
            self.unit * level
            + ("return " + self.expr(s.value) if s.value is not None else "return")
            + ";"
        ]

    def body(self, s: A.Node, level: int, dangling: bool = False) -> list[str]:
        # An `if` without `else` as the then-branch of an if/else needs braces, or the else
        # would attach to it (6.2): wrap it.
        if dangling and isinstance(s, A.If) and _ends_open(s):
            return self.stmt(A.Compound(stmts=[s]), level)
        if isinstance(s, A.Compound):
            return self.stmt(s, level)
        return self.stmt(s, level + 1)

    def condition(self, c: A.Node) -> str:
        if isinstance(c, A.ConditionDeclaration):
            return (
                f"{self.qualifiers(c.qualifiers)}{self.type(c.type)} {c.name} = "
                f"{self.expr(c.init, PRECEDENCE['='])}"
            )
        assert isinstance(c, A.Expr)  # a condition is an expression or a declaration
        return self.expr(c)

    # -- expressions ---------------------------------------------------------------------------
    def expr(self, e: A.Expr, context: int = 0) -> str:
        text, prec = self.dispatch("_expr_", e)
        return f"({text})" if prec < context else text

    def _expr_Identifier(self, e: A.Identifier) -> tuple[str, int]:
        return e.name, PRIMARY

    def _expr_IntLiteral(self, e: A.IntLiteral) -> tuple[str, int]:
        return e.text or (str(e.value) + ("u" if e.unsigned else "")), PRIMARY

    def _expr_FloatLiteral(self, e: A.FloatLiteral) -> tuple[str, int]:
        return e.text or repr(e.value), PRIMARY

    def _expr_BoolLiteral(self, e: A.BoolLiteral) -> tuple[str, int]:
        return ("true" if e.value else "false"), PRIMARY

    def _expr_Binary(self, e: A.Binary) -> tuple[str, int]:
        p = PRECEDENCE[e.op]
        # Left-associative: the right operand needs parentheses at equal precedence.
        return f"{self.expr(e.left, p)} {e.op} {self.expr(e.right, p + 1)}", p

    def _expr_Assignment(self, e: A.Assignment) -> tuple[str, int]:
        p = PRECEDENCE["="]
        return f"{self.expr(e.target, UNARY)} {e.op} {self.expr(e.value, p)}", p

    def _expr_Ternary(self, e: A.Ternary) -> tuple[str, int]:
        p = PRECEDENCE["?:"]
        return f"{self.expr(e.cond, p + 1)} ? {self.expr(e.then)} : {self.expr(e.else_, p)}", p

    def _expr_Sequence(self, e: A.Sequence) -> tuple[str, int]:
        return ", ".join(self.expr(x, PRECEDENCE["="]) for x in e.exprs), PRECEDENCE[","]

    def _expr_Unary(self, e: A.Unary) -> tuple[str, int]:
        inner = self.expr(e.operand, UNARY)
        # `- -x` and `+ +x` must not fuse into `--x` / `++x`.
        sep = " " if inner[:1] in "+-" and e.op in ("+", "-", "++", "--") else ""
        return f"{e.op}{sep}{inner}", UNARY

    def _expr_Postfix(self, e: A.Postfix) -> tuple[str, int]:
        return f"{self.expr(e.operand, POSTFIX)}{e.op}", POSTFIX

    def _expr_Call(self, e: A.Call) -> tuple[str, int]:
        callee = self.struct(e.struct_) if e.struct_ is not None else e.callee
        args = ", ".join(self.expr(a, PRECEDENCE["="]) for a in e.args)
        return f"{callee}{self.array(e.array)}({args})", POSTFIX

    def _expr_Index(self, e: A.Index) -> tuple[str, int]:
        return f"{self.expr(e.base, POSTFIX)}[{self.expr(e.index)}]", POSTFIX

    def _expr_Field(self, e: A.Field) -> tuple[str, int]:
        base = self.expr(e.base, POSTFIX)
        if isinstance(e.base, A.IntLiteral | A.FloatLiteral):
            base = f"({base})"
        return f"{base}.{e.name}", POSTFIX

    def _expr_MethodCall(self, e: A.MethodCall) -> tuple[str, int]:
        return f"{self.expr(e.base, POSTFIX)}.{e.name}()", POSTFIX


def _ends_open(s: A.Node) -> bool:
    """Does this statement end with an `if` that has no `else` (so a following else binds to it)?"""
    while True:
        if isinstance(s, A.If):
            if s.else_ is None:
                return True
            s = s.else_
        elif isinstance(s, (A.While, A.For)):
            s = s.body
        else:
            return False
