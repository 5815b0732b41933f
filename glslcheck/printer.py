"""The GLSL printer: AST -> GLSL ES 3.00 source (`glslcheck parse --print`).

Many tiny `_print_<Node>` methods. Parentheses come from one precedence table (GLSL ES 3.00
section 5.1), the same ladder grammar/glsl.lark encodes; tests/parse/test_printer.py checks
that the two agree for every pair of binary operators. Printing then parsing gives back the
same tree (`ast.dump` equal), which the corpus round-trip test checks.
"""

from __future__ import annotations

from . import ast as A

# Higher binds tighter (GLSL ES 3.00 5.1, numbered from the comma operator up).
PRECEDENCE = {
    ",": 1,
    "=": 2, "+=": 2, "-=": 2, "*=": 2, "/=": 2, "%=": 2, "<<=": 2, ">>=": 2, "&=": 2, "^=": 2, "|=": 2,
    "?:": 3,
    "||": 4,
    "^^": 5,
    "&&": 6,
    "|": 7,
    "^": 8,
    "&": 9,
    "==": 10, "!=": 10,
    "<": 11, ">": 11, "<=": 11, ">=": 11,
    "<<": 12, ">>": 12,
    "+": 13, "-": 13,
    "*": 14, "/": 14, "%": 14,
}
UNARY = 15
POSTFIX = 16
PRIMARY = 17


def to_glsl(node: A.Node, indent: str = "    ") -> str:
    """GLSL source for a tree (a TranslationUnit, a statement or an expression)."""
    return _Printer(indent).print(node)


class _Printer:
    def __init__(self, indent: str) -> None:
        self.unit = indent

    def print(self, node: A.Node) -> str:
        if isinstance(node, A.Expr):
            return self.expr(node)
        if isinstance(node, A.Stmt):
            return "\n".join(self.stmt(node, 0)) + "\n"
        return getattr(self, "_print_" + type(node).__name__)(node)

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
                ids = ", ".join(i.name if i.value is None else f"{i.name} = {i.value}" for i in lay.ids)
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
        if isinstance(d, A.VariableDeclaration):
            decls = ", ".join(self.declarator(x) for x in d.declarators)
            head = f"{self.qualifiers(d.qualifiers)}{self.type(d.type)}"
            return f"{head} {decls}" if decls else head
        if isinstance(d, A.FunctionDeclaration):
            return self.prototype(d.proto)
        if isinstance(d, A.PrecisionDeclaration):
            return f"precision {d.precision} {self.type(d.type)}"
        if isinstance(d, A.BlockDeclaration):
            pad = self.unit * (level + 1)
            members = "".join(f"\n{pad}{self.member(m)};" for m in d.members)
            inst = f" {d.instance}{self.array(d.array)}" if d.instance else ""
            return f"{self.qualifiers(d.qualifiers)}{d.block_name} {{{members}\n{self.unit * level}}}{inst}"
        if isinstance(d, A.InvariantDeclaration):
            return f"{self.qualifiers(d.qualifiers)}{', '.join(d.names)}"
        if isinstance(d, A.QualifierDeclaration):
            return self.qualifiers(d.qualifiers).rstrip()
        raise TypeError(f"cannot print {type(d).__name__}")

    def declarator(self, d: A.Declarator) -> str:
        text = d.name + self.array(d.array)
        if d.init is not None:
            text += " = " + self.expr(d.init, PRECEDENCE["="])
        return text

    # -- statements ----------------------------------------------------------------------------
    def stmt(self, s: A.Node, level: int) -> list[str]:
        pad = self.unit * level
        if isinstance(s, A.Compound):
            lines = [pad + "{"]
            for x in s.stmts:
                lines.extend(self.stmt(x, level + 1))
            lines.append(pad + "}")
            return lines
        if isinstance(s, A.DeclarationStatement):
            return [pad + self.declaration(s.decl, level) + ";"]
        if isinstance(s, A.ExpressionStatement):
            return [pad + (self.expr(s.expr) if s.expr is not None else "") + ";"]
        if isinstance(s, A.If):
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
        if isinstance(s, A.Switch):
            lines = [f"{pad}switch ({self.expr(s.expr)})", pad + "{"]
            for x in s.body:
                lines.extend(self.stmt(x, level + (0 if isinstance(x, A.Case) else 1)))
            lines.append(pad + "}")
            return lines
        if isinstance(s, A.Case):
            return [f"{pad}case {self.expr(s.expr)}:" if s.expr is not None else f"{pad}default:"]
        if isinstance(s, A.While):
            return [f"{pad}while ({self.condition(s.cond)})", *self.body(s.body, level)]
        if isinstance(s, A.DoWhile):
            return [f"{pad}do", *self.body(s.body, level), f"{pad}while ({self.expr(s.cond)});"]
        if isinstance(s, A.For):
            init = self.stmt(s.init, 0)[0] if s.init is not None else ";"
            cond = self.condition(s.cond) if s.cond is not None else ""
            step = self.expr(s.step) if s.step is not None else ""
            return [f"{pad}for ({init} {cond}; {step})".replace("( ", "(").replace(" ;", ";"), *self.body(s.body, level)]
        if isinstance(s, A.Break):
            return [pad + "break;"]
        if isinstance(s, A.Continue):
            return [pad + "continue;"]
        if isinstance(s, A.Discard):
            return [pad + "discard;"]
        if isinstance(s, A.Return):
            return [pad + ("return " + self.expr(s.value) if s.value is not None else "return") + ";"]
        raise TypeError(f"cannot print {type(s).__name__}")

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
            return f"{self.qualifiers(c.qualifiers)}{self.type(c.type)} {c.name} = {self.expr(c.init, PRECEDENCE['='])}"
        return self.expr(c)

    # -- expressions ---------------------------------------------------------------------------
    def expr(self, e: A.Expr, context: int = 0) -> str:
        text, prec = self._expr(e)
        return f"({text})" if prec < context else text

    def _expr(self, e: A.Expr) -> tuple[str, int]:
        if isinstance(e, A.Identifier):
            return e.name, PRIMARY
        if isinstance(e, A.IntLiteral):
            return e.text or (str(e.value) + ("u" if e.unsigned else "")), PRIMARY
        if isinstance(e, A.FloatLiteral):
            return e.text or repr(e.value), PRIMARY
        if isinstance(e, A.BoolLiteral):
            return ("true" if e.value else "false"), PRIMARY
        if isinstance(e, A.Binary):
            p = PRECEDENCE[e.op]
            # Left-associative: the right operand needs parentheses at equal precedence.
            return f"{self.expr(e.left, p)} {e.op} {self.expr(e.right, p + 1)}", p
        if isinstance(e, A.Assignment):
            p = PRECEDENCE["="]
            return f"{self.expr(e.target, UNARY)} {e.op} {self.expr(e.value, p)}", p
        if isinstance(e, A.Ternary):
            p = PRECEDENCE["?:"]
            return f"{self.expr(e.cond, p + 1)} ? {self.expr(e.then)} : {self.expr(e.else_, p)}", p
        if isinstance(e, A.Sequence):
            return ", ".join(self.expr(x, PRECEDENCE["="]) for x in e.exprs), PRECEDENCE[","]
        if isinstance(e, A.Unary):
            inner = self.expr(e.operand, UNARY)
            # `- -x` and `+ +x` must not fuse into `--x` / `++x`.
            sep = " " if inner[:1] in "+-" and e.op in ("+", "-", "++", "--") else ""
            return f"{e.op}{sep}{inner}", UNARY
        if isinstance(e, A.Postfix):
            return f"{self.expr(e.operand, POSTFIX)}{e.op}", POSTFIX
        if isinstance(e, A.Call):
            callee = self.struct(e.struct_) if e.struct_ is not None else e.callee
            args = ", ".join(self.expr(a, PRECEDENCE["="]) for a in e.args)
            return f"{callee}{self.array(e.array)}({args})", POSTFIX
        if isinstance(e, A.Index):
            return f"{self.expr(e.base, POSTFIX)}[{self.expr(e.index)}]", POSTFIX
        if isinstance(e, A.Field):
            base = self.expr(e.base, POSTFIX)
            if isinstance(e.base, A.IntLiteral | A.FloatLiteral):
                base = f"({base})"
            return f"{base}.{e.name}", POSTFIX
        if isinstance(e, A.MethodCall):
            return f"{self.expr(e.base, POSTFIX)}.{e.name}()", POSTFIX
        raise TypeError(f"cannot print {type(e).__name__}")


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
