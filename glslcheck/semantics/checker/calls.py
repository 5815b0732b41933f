"""Calls and constructors: overload resolution of user and built-in functions, and type
constructors.

Owns a call's target (a user overload matched exactly, or a built-in from
`language/builtin_functions.py`), `out`/`inout` arguments (they must be variables), constant
offsets of texture lookups, constructors of vectors, matrices, structs and arrays, and the
constant value of a built-in call or constructor of constants.
"""

from __future__ import annotations

from ...frontend import syntax as A
from ...language import builtin_functions as B
from ...language import glsl_types as T
from .. import consteval as C
from ..model import ERROR, Constructor
from .hints import NameAt, int_literal_hint
from .state import CheckerState


class CallChecks(CheckerState):
    """Function calls and constructors, for `Checker`."""

    # -- calls ---------------------------------------------------------------------------------
    def expr_Call(self, n: A.Call) -> T.Type:
        if n.constructor:
            return self.constructor(n)
        name = n.callee
        sym = self.scope.lookup(name)
        if sym is not None and sym.kind == "struct":
            return self.constructor(n)
        arg_types = [self.expr(a) for a in n.args]
        where = NameAt(n, "callee_loc")
        if sym is not None and sym.kind != "function":
            self.error(
                f"'{name}' is a variable, not a function",
                where,
                help="a local variable with this name hides the function; rename the variable",
            )
            return ERROR
        if ERROR in arg_types:
            return ERROR
        if sym is None:
            if B.is_builtin_function(name):
                return self.builtin_call(n, name, arg_types)
            self.error(
                f"'{name}' is not declared", where, help=self.did_you_mean(name, functions=True)
            )
            return ERROR
        overloads = self.model.functions.get(name, [])
        shown = f"{name}({', '.join(map(str, arg_types))})"
        for fn in overloads:
            if [t for _, t, _ in fn.params] == arg_types:
                self.model._calls[id(n)] = fn
                self.model._calls_from.setdefault(self.func, []).append((n, fn))
                for arg, (_, _, direction) in zip(n.args, fn.params):
                    if direction in ("out", "inout"):
                        self._out_argument(arg, direction, name)
                return fn.type
        cands = "; ".join(fn.signature() for fn in overloads)
        hint = None
        if len(overloads) == 1 and len(overloads[0].params) == len(arg_types):
            for i, ((_, want, _), got, arg) in enumerate(
                zip(overloads[0].params, arg_types, n.args)
            ):
                if want != got:
                    h = int_literal_hint(arg) if want.base == "float" else None
                    hint = f"argument {i + 1} is '{got}' but the parameter is '{want}'" + (
                        f": {h}" if h else ""
                    )
                    break
        self.error(
            f"no function '{shown}' matches the arguments; candidates: {cands}", where, help=hint
        )
        return ERROR

    def _out_argument(self, arg: A.Node, direction: str, fname: str) -> None:
        why = self.lvalue_problem(arg)
        if why is not None:
            self.error(
                f"the argument for an '{direction}' parameter of '{fname}' must be a variable: "
                f"{why}",
                arg,
                help="pass a local variable and copy it afterwards",
            )

    def builtin_call(self, n: A.Call, name: str, arg_types: list[T.Type]) -> T.Type:
        ov = B.resolve(name, arg_types)
        if isinstance(ov, str):
            hint = None
            if any(t.base == "int" for t in arg_types) and any(
                t.base == "float" for t in arg_types
            ):
                for arg, t in zip(n.args, arg_types):
                    h = int_literal_hint(arg) if t.base == "int" else None
                    if h:
                        hint = h
                        break
                hint = (
                    hint
                    or "GLSL ES has no implicit int-to-float conversion: convert with float(...)"
                )
            self.error(ov, n.callee_loc if n.callee_loc.line else n, help=hint)
            return ERROR
        self.model._calls[id(n)] = ov
        self.model._calls_from.setdefault(self.func, []).append((n, ov))
        for i in ov.out_params:
            self._out_argument(n.args[i], "out", name)
        if name in B.CONSTANT_OFFSET_FUNCTIONS:
            offset = self._offset_index(ov)
            if offset is not None and not self.is_const(n.args[offset]):
                self.error(
                    f"the offset argument of {name}() must be a constant expression",
                    n.args[offset],
                    help="use literals or consts, e.g. ivec2(1, 0)",
                )
        if (
            ov.category != B.TEXTURE
            and ov.category != B.DERIVATIVE
            and all(self.is_const(a) for a in n.args)
        ):
            self.consts[id(n)] = C.builtin(
                name, ov.params, ov.returns, [self.consts[id(a)] for a in n.args]
            )
        return ov.returns

    @staticmethod
    def _offset_index(ov: B.Overload) -> int | None:
        idx = [i for i, p in enumerate(ov.params) if p.is_vector and p.base == "int"]
        return idx[-1] if idx else None

    # -- constructors --------------------------------------------------------------------------
    def constructor(self, n: A.Call) -> T.Type:
        arg_types = [self.expr(a) for a in n.args]
        where = NameAt(n, "callee_loc")
        if n.struct_ is not None:
            target = self.struct(n.struct_)
        elif n.callee in T.BY_NAME:
            target = T.BY_NAME[n.callee]
        else:
            sym = self.scope.lookup(n.callee)
            if sym is None or sym.kind != "struct":
                self.error(f"'{n.callee}' is not a type", where)
                return ERROR
            target = sym.type
        if n.array is not None:
            if target.is_array:
                self.error("arrays of arrays are not available in GLSL ES 3.00", n.array)
                return ERROR
            size = self.array_size(n.array)
            if size is ERROR:
                return ERROR
            target = T.ArrayType(target, size)
        if ERROR in arg_types or target is ERROR:
            return ERROR
        res = T.constructor_result(target, arg_types)
        if isinstance(res, str):
            hint = None
            if isinstance(target, (T.StructType, T.ArrayType)):
                wants = (
                    [target.element] * len(arg_types)
                    if isinstance(target, T.ArrayType)
                    else [f for _, f in target.fields]
                )
                for arg, t, want in zip(n.args, arg_types, wants):
                    if want is not None and want.base == "float" and t.base == "int":
                        hint = int_literal_hint(arg)
                        break
            self.error(res, where, help=hint)
            return ERROR
        self.model._calls[id(n)] = Constructor(res)
        if all(self.is_const(a) for a in n.args):
            self.consts[id(n)] = C.construct(res, arg_types, [self.consts[id(a)] for a in n.args])
        return res
