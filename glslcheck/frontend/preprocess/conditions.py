"""`#if` and `#elif` expressions: `defined` resolved, macros expanded, then evaluated with 32-bit
integer arithmetic as C does (`&&` and `||` short-circuit, so an undefined name on the side not
taken is no error).
"""

from __future__ import annotations

from ...base.diagnostics import GlslError
from ...base.regexes import compiled
from .context import PreprocessorState
from .expansion import expand_list
from .tokens import ID, NUM, OP, Token

MAX_IF_NESTING = 100  # parentheses and unary operators in one #if expression
_BINARY_PREC = {
    "||": 1,
    "&&": 2,
    "|": 3,
    "^": 4,
    "&": 5,
    "==": 6,
    "!=": 6,
    "<": 7,
    ">": 7,
    "<=": 7,
    ">=": 7,
    "<<": 8,
    ">>": 8,
    "+": 9,
    "-": 9,
    "*": 10,
    "/": 10,
    "%": 10,
}
INTEGER_RE = compiled(r"0[xX][0-9A-Fa-f]+|0[0-7]*|[1-9][0-9]*")


def wrap32(v: int) -> int:
    v &= 0xFFFFFFFF
    return v - 0x100000000 if v & 0x80000000 else v


def eval_if(pp: PreprocessorState, toks: list[Token], directive: Token) -> bool:
    if not toks:
        raise pp.token_error(f"#{directive.text} needs an expression", directive)
    # `defined X` and `defined(X)` are resolved before macro expansion.
    pre: list[Token] = []
    i = 0
    while i < len(toks):
        t = toks[i]
        if t.kind == ID and t.text == "defined":
            if i + 1 < len(toks) and toks[i + 1].kind == ID:
                target, i = toks[i + 1], i + 2
                end = target.end
            elif (
                i + 3 < len(toks)
                and toks[i + 1].text == "("
                and toks[i + 2].kind == ID
                and toks[i + 3].text == ")"
            ):
                target, end, i = toks[i + 2], toks[i + 3].end, i + 4
            else:
                raise pp.token_error(
                    "'defined' needs a macro name: defined NAME or defined(NAME)", t
                )
            pre.append(Token(NUM, "1" if target.text in pp.macros else "0", t.start, end, t.ws))
            continue
        pre.append(t)
        i += 1
    expr = expand_list(pp, pre, 0)
    if not expr:
        raise pp.token_error(
            f"#{directive.text} needs an expression (the macros expand to nothing)", directive
        )
    ev = IfEvaluator(pp, expr, directive)
    value = ev.expression(1, True, 0)
    if ev.i < len(expr):
        t = expr[ev.i]
        raise pp.token_error(f"unexpected '{t.text}' in the #{directive.text} expression", t)
    return value != 0


class IfEvaluator:
    """Evaluates the tokens of an #if line (after expansion) with 32-bit integer arithmetic."""

    def __init__(self, pp: PreprocessorState, toks: list[Token], directive: Token):
        self.pp = pp
        self.toks = toks
        self.i = 0
        self.directive = directive

    def _peek(self) -> Token | None:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def _fail(self, message: str, t: Token | None) -> GlslError:
        return self.pp.token_error(message, t or self.toks[-1])

    def expression(self, min_prec: int, live: bool, nesting: int) -> int:
        lhs = self.unary(live, nesting)
        while True:
            t = self._peek()
            if t is None or t.kind != OP:
                return lhs
            prec = _BINARY_PREC.get(t.text)
            if prec is None or prec < min_prec:
                return lhs
            self.i += 1
            op = t.text
            if op == "&&":
                rhs = self.expression(prec + 1, live and lhs != 0, nesting)
                lhs = int(lhs != 0 and rhs != 0)
            elif op == "||":
                rhs = self.expression(prec + 1, live and lhs == 0, nesting)
                lhs = int(lhs != 0 or rhs != 0)
            else:
                rhs = self.expression(prec + 1, live, nesting)
                lhs = self._binary(op, lhs, rhs, t)

    def _binary(self, op: str, a: int, b: int, t: Token) -> int:
        if op in ("/", "%"):
            if b == 0:
                raise self._fail(f"division by zero in #{self.directive.text}", t)
            q = abs(a) // abs(b) * (1 if (a < 0) == (b < 0) else -1)
            return wrap32(q if op == "/" else a - q * b)
        if op in ("<<", ">>"):
            b &= 31
            return wrap32(a << b) if op == "<<" else a >> b
        return wrap32(
            {
                "*": lambda: a * b,
                "+": lambda: a + b,
                "-": lambda: a - b,
                "<": lambda: int(a < b),
                ">": lambda: int(a > b),
                "<=": lambda: int(a <= b),
                ">=": lambda: int(a >= b),
                "==": lambda: int(a == b),
                "!=": lambda: int(a != b),
                "&": lambda: a & b,
                "^": lambda: a ^ b,
                "|": lambda: a | b,
            }[op]()
        )

    def unary(self, live: bool, nesting: int) -> int:
        if nesting > MAX_IF_NESTING:
            raise self._fail(
                f"the #{self.directive.text} expression is nested too deeply", self._peek()
            )
        t = self._peek()
        if t is None:
            raise self._fail(f"the #{self.directive.text} expression ends too early", None)
        self.i += 1
        if t.kind == OP and t.text in ("+", "-", "~", "!"):
            v = self.unary(live, nesting + 1)
            return {"+": v, "-": wrap32(-v), "~": wrap32(~v), "!": int(v == 0)}[t.text]
        if t.kind == OP and t.text == "(":
            v = self.expression(1, live, nesting + 1)
            close = self._peek()
            if close is None or close.text != ")":
                raise self._fail("a ')' is missing in the #if expression", close)
            self.i += 1
            return v
        if t.kind == NUM:
            if not INTEGER_RE.fullmatch(t.text):
                raise self._fail(
                    f"#if expressions use integers only; '{t.text}' is not an integer literal", t
                )
            v = (
                int(t.text, 0)
                if not (t.text.startswith("0") and t.text[1:].isdigit())
                else int(t.text, 8)
            )
            if v > 0xFFFFFFFF:
                raise self._fail(f"the number '{t.text}' is too large for an #if expression", t)
            return wrap32(v)
        if t.kind == ID:
            if live:
                raise self._fail(f"undefined macro '{t.text}' in #{self.directive.text}", t)
            return 0
        raise self._fail(f"unexpected '{t.text}' in the #{self.directive.text} expression", t)
