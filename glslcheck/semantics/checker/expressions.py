"""Expressions and operators: the type (and constant value) of literals, names, operators and
accesses.

Owns exact-match typing of operators (no implicit conversions; the rules are in
`language/glsl_types.py`), l-values, `?:`, indexes (constant ones within range), struct fields,
swizzles and `.length()`, and the constant value of every constant expression (`consteval.py`).
Expressions go to `expr_<Node>` methods (`syntax.NodeVisitor.dispatch`); calls and constructors
are in calls.py.
"""

from __future__ import annotations

from ...base.precision import float32_literal
from ...frontend import syntax as A
from ...language import builtin_functions as B
from ...language import glsl_types as T
from .. import consteval as C
from .. import webgl_rules
from ..model import ERROR, Symbol
from .hints import int_literal_hint
from .shadertoy_rules import RENAMED_UNIFORMS
from .state import CheckerState


class ExpressionChecks(CheckerState):
    """Expressions other than calls, for `Checker`."""

    # -- literals and names --------------------------------------------------------------------
    def expr_IntLiteral(self, n: A.IntLiteral) -> T.Type:
        self.consts[id(n)] = n.value
        return T.UINT if n.unsigned else T.INT

    def expr_FloatLiteral(self, n: A.FloatLiteral) -> T.Type:
        self.consts[id(n)] = (
            float32_literal(n.text) if n.text else C.f32(n.value)
        )  # the decimal rounded once
        return T.FLOAT

    def expr_BoolLiteral(self, n: A.BoolLiteral) -> T.Type:
        self.consts[id(n)] = n.value
        return T.BOOL

    def expr_Identifier(self, n: A.Identifier) -> T.Type:
        sym = self.scope.lookup(n.name)
        if sym is None:
            self._undeclared(n)
            return ERROR
        if sym.kind == "function":
            self.error(f"'{n.name}' is a function; call it with arguments: {n.name}(...)", n)
            return ERROR
        if sym.kind == "struct":
            self.error(
                f"'{n.name}' is a struct type, not a value",
                n,
                help=f"construct one with {n.name}(...)",
            )
            return ERROR
        self.symbols[id(n)] = sym
        if sym.kind == "uniform":
            if (
                n.loc.path in self.common_paths
                and n.name not in B.COMMON_TAB_UNIFORMS
                and not self.in_macro_entry()
            ):
                self.common_uniform_error(n)
            self.model._uniforms_from.setdefault(self.func, set()).add(n.name)
        if sym.qualifier == "const" and sym.kind != "param":
            self.consts[id(n)] = sym.const_value if sym.const_value is not None else C.UNKNOWN
        return sym.type

    def _undeclared(self, n: A.Identifier) -> None:
        if n.name in B.SHADERTOY_UNIFORMS and not self.plain:
            # Only the Common tab compiled alone lacks Shadertoy's uniforms.
            self.common_uniform_error(n)
            return
        if B.is_builtin_function(n.name):
            self.error(
                f"'{n.name}' is a built-in function; call it with arguments: {n.name}(...)", n
            )
            return
        if n.name in RENAMED_UNIFORMS and not self.plain:
            new = RENAMED_UNIFORMS[n.name]
            self.error(
                f"'{n.name}' is Shadertoy's old name for '{new}', which Shadertoy no longer "
                "declares",
                n,
                help=f"replace '{n.name}' with '{new}'",
            )
            return
        self.error(f"'{n.name}' is not declared", n, help=self.did_you_mean(n.name))

    def did_you_mean(self, name: str, functions: bool = False, structs: bool = False) -> str | None:
        if structs:
            known = [
                s
                for s in self.scope.visible_names()
                if (self.scope.lookup(s) or Symbol("", "", T.VOID)).kind == "struct"
            ]
            known += [k for k in T.BY_NAME]
        elif functions:
            known = list(self.model.functions) + list(B.BUILTINS)
        else:
            known = [k for k in self.scope.visible_names() if not k.startswith("gl_Max")]
        import difflib  # only for an error's suggestion: not at every start-up

        match = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
        if match:
            return f"did you mean '{match[0]}'?"
        return None

    # -- operators -----------------------------------------------------------------------------
    def expr_Binary(self, n: A.Binary) -> T.Type:
        lt = self.expr(n.left)
        rt = self.expr(n.right)
        if lt is ERROR or rt is ERROR:
            return ERROR
        res = T.binary_result(n.op, lt, rt)
        if isinstance(res, str):
            hint = self._mix_hint(n.left, lt, n.right, rt)
            if hint and hint.startswith("write"):
                res = (
                    res.split(": GLSL ES has no implicit", 1)[0]
                    + f": GLSL ES has no implicit conversion; {hint}"
                )
            self.error(res, n, help=hint)
            return ERROR
        if self.is_const(n.left) and self.is_const(n.right):
            self.consts[id(n)] = C.binary(
                n.op, lt, rt, res, self.consts[id(n.left)], self.consts[id(n.right)]
            )
        return res

    def _mix_hint(self, left: A.Node, lt: T.Type, right: A.Node, rt: T.Type) -> str | None:
        """'write 2.0' when an int literal meets a float (and the reverse)."""
        if lt.base == "float" and rt.base == "int":
            return int_literal_hint(right) or "convert the int: float(...)"
        if rt.base == "float" and lt.base == "int":
            return int_literal_hint(left) or "convert the int: float(...)"
        if lt.base == "int" and rt.base == "uint" or lt.base == "uint" and rt.base == "int":
            return "add a 'u' suffix to the literal, or convert with uint(...) / int(...)"
        return None

    def expr_Unary(self, n: A.Unary) -> T.Type:
        t, res = self._unary(n)
        if res is ERROR:
            return ERROR
        if n.op in ("++", "--"):
            self.require_lvalue(n.operand, f"'{n.op}'")
        elif self.is_const(n.operand):
            self.consts[id(n)] = C.unary(n.op, t, self.consts[id(n.operand)])
        return res

    def expr_Postfix(self, n: A.Postfix) -> T.Type:
        _, res = self._unary(n)
        if res is not ERROR:
            self.require_lvalue(n.operand, f"'{n.op}'")
        return res

    def _unary(self, n: A.Unary | A.Postfix) -> tuple[T.Type, T.Type]:
        """(the operand's type, the result's) of a prefix or postfix operator; the result is
        ERROR after an error (the operator's is reported here)."""
        t = self.expr(n.operand)
        if t is ERROR:
            return t, ERROR
        res = T.unary_result(n.op, t)
        if isinstance(res, str):
            self.error(res, n)
            return t, ERROR
        return t, res

    def expr_Assignment(self, n: A.Assignment) -> T.Type:
        tt = self.expr(n.target)
        vt = self.expr(n.value)
        if tt is ERROR or vt is ERROR:
            if tt is not ERROR:
                self.require_lvalue(n.target, "assignment")
            return ERROR
        res = T.assign_result(n.op, tt, vt)
        if isinstance(res, str):
            hint = None
            if tt.base == "float" and vt.base == "int":
                hint = int_literal_hint(n.value) or "convert the value: float(...)"
            self.error(
                res + (f"; {hint}" if hint and hint.startswith("write") else ""), n, help=hint
            )
            self.require_lvalue(n.target, "assignment")
            return ERROR
        self.require_lvalue(n.target, "assignment")
        return res

    def require_lvalue(self, node: A.Node, what: str) -> bool:
        why = self.lvalue_problem(node)
        if why is None:
            return True
        self.error(f"cannot modify this: {why}", node, help=None)
        return False

    def lvalue_problem(self, node: A.Node) -> str | None:
        if isinstance(node, A.Identifier):
            sym = self.symbols.get(id(node))
            if sym is None:
                return None  # already reported
            if sym.kind == "uniform" or sym.qualifier == "uniform":
                return f"'{node.name}' is a uniform (read-only)"
            if sym.qualifier == "const":
                return f"'{node.name}' is const" + (
                    " (a const parameter)" if sym.kind == "param" else ""
                )
            if sym.kind == "builtin-var" and sym.qualifier != "out":
                return f"'{node.name}' is a read-only built-in variable"
            if sym.kind == "global" and sym.qualifier in ("in", "centroid in"):
                return f"'{node.name}' is a shader input (read-only)"
            return None
        if isinstance(node, A.Field):
            if id(node) in self.model._swizzles:
                idx = self.model._swizzles[id(node)]
                if len(set(idx)) != len(idx):
                    return f"the swizzle '.{node.name}' repeats a component"
            return self.lvalue_problem(node.base)
        if isinstance(node, A.Index):
            return self.lvalue_problem(node.base)
        if isinstance(node, A.Call):
            return "a function call's result is not a variable"
        if isinstance(node, (A.IntLiteral, A.FloatLiteral, A.BoolLiteral)):
            return "a literal is not a variable"
        return "this expression is not a variable"

    def expr_Ternary(self, n: A.Ternary) -> T.Type:
        ct = self.expr(n.cond)
        a = self.expr(n.then)
        b = self.expr(n.else_)
        if ct is not ERROR and ct != T.BOOL:
            self.error(f"the condition of '?:' must be a bool, not '{ct}'", n.cond)
            return ERROR
        if a is ERROR or b is ERROR or ct is ERROR:
            return ERROR
        if a != b:
            hint = None
            if a.base == "float" and b.base == "int":
                hint = int_literal_hint(n.else_)
            elif b.base == "float" and a.base == "int":
                hint = int_literal_hint(n.then)
            self.error(
                f"the two branches of '?:' have different types, '{a}' and '{b}'",
                n,
                help=hint or "convert one branch so both have the same type",
            )
            return ERROR
        if a.is_void:
            self.error("the branches of '?:' cannot be void", n)
            return ERROR
        self.webgl(webgl_rules.ternary_problem(a), n)
        if self.is_const(n.cond) and self.is_const(n.then) and self.is_const(n.else_):
            c = self.consts[id(n.cond)]
            self.consts[id(n)] = (
                C.UNKNOWN if c is C.UNKNOWN else self.consts[id(n.then if c else n.else_)]
            )
        return a

    def expr_Sequence(self, n: A.Sequence) -> T.Type:
        t: T.Type = ERROR
        for e in n.exprs:
            t = self.expr(e)
        return t

    # -- indexes, fields and methods -----------------------------------------------------------
    def expr_Index(self, n: A.Index) -> T.Type:
        bt = self.expr(n.base)
        it = self.expr(n.index)
        if bt is ERROR or it is ERROR:
            return ERROR
        res = T.index_result(bt)
        if isinstance(res, str):
            self.error(res, n.base)
            return ERROR
        if it not in (T.INT, T.UINT):
            hint = "convert it: int(...)" if it == T.FLOAT else None
            self.error(f"an index must be an int or uint, not '{it}'", n.index, help=hint)
            return ERROR
        if self.is_const(n.index):
            v = self.model.const_value(n.index)
            size = (
                bt.array_size
                if isinstance(bt, T.ArrayType)
                else (bt.cols if bt.is_matrix else bt.size)
            )
            what = "array" if bt.is_array else ("matrix" if bt.is_matrix else "vector")
            if v is not None and (v < 0 or (size is not None and v >= size)):
                self.error(
                    f"index {v} is out of range for this {what} of {size} "
                    f"{'elements' if bt.is_array else 'columns' if bt.is_matrix else 'components'}"
                    f" (valid: 0 to {size - 1})"
                    if size
                    else f"index {v} is out of range",
                    n.index,
                )
                return ERROR
            if self.is_const(n.base):
                self.consts[id(n)] = C.index(self.consts[id(n.base)], v)
        return res

    def expr_Field(self, n: A.Field) -> T.Type:
        bt = self.expr(n.base)
        if bt is ERROR:
            return ERROR
        if isinstance(bt, T.StructType):
            ft = bt.field_type(n.name)
            if ft is None:
                import difflib

                names = [f for f, _ in bt.fields]
                match = difflib.get_close_matches(n.name, names, n=1)
                self.error(
                    f"the struct '{bt}' has no member '{n.name}'",
                    n.name_loc if n.name_loc.line else n,
                    help=(
                        f"did you mean '{match[0]}'?"
                        if match
                        else f"its members are: {', '.join(names)}"
                    ),
                )
                return ERROR
            if self.is_const(n.base):
                i = [f for f, _ in bt.fields].index(n.name)
                v = self.consts[id(n.base)]
                self.consts[id(n)] = C.index(v, i)
            return ft
        res = T.swizzle_result(bt, n.name)
        if isinstance(res, str):
            self.error(res, n.name_loc if n.name_loc.line else n)
            return ERROR
        letters = next(s for s in T.SWIZZLE_SETS if all(c in s for c in n.name))
        idx = tuple(letters.index(c) for c in n.name)
        self.model._swizzles[id(n)] = idx
        if self.is_const(n.base):
            self.consts[id(n)] = C.swizzle(self.consts[id(n.base)], idx)
        return res

    def expr_MethodCall(self, n: A.MethodCall) -> T.Type:
        bt = self.expr(n.base)
        if bt is ERROR:
            return ERROR
        if n.name != "length":
            self.error(
                f"'.{n.name}()' is not a method: GLSL ES 3.00 has only '.length()' of arrays", n
            )
            return ERROR
        if not isinstance(bt, T.ArrayType):
            hint = "use length(v) for the Euclidean length of a vector" if bt.is_vector else None
            self.error(f"'.length()' applies to arrays only, not '{bt}'", n, help=hint)
            return ERROR
        if bt.array_size is not None:
            self.consts[id(n)] = bt.array_size
        return T.INT
