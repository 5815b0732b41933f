"""Names and constants of the generated module: emitting lines, fresh temporaries, the mangled
Python names of GLSL variables, functions, struct types and members, module constants and
zero values. Mixed into `Transpiler`."""

from __future__ import annotations

from typing import Any

from ....base.diagnostics import Location
from ....semantics.model import Symbol
from ...cpu_core.common import IDENT, comment_safe, python_ident
from .common import _error
from .state import TranspilerState


class Names(TranspilerState):
    """The naming and constant pass of `Transpiler` (see the package docstring for the scheme)."""

    # -- small emission helpers ----------------------------------------------------------------
    def emit(self, text: str) -> None:
        self.lines.append("    " * self.indent + text)

    def fresh(self, prefix: str) -> str:
        self.n += 1
        name = f"_{prefix}{self.n}"
        if self.fn is not None:
            self.fn.defined.append(name)
        return name

    def comment_line(self, node: Any) -> None:
        loc = getattr(node, "loc", None)
        if loc is None or not loc.line:
            return
        key = (loc.path, loc.line)
        if key == self.last_line:
            return
        self.last_line = key
        from ....base.diagnostics import source_line

        text = source_line(loc.path, loc.line) or ""
        where = (
            f"line {loc.line}"
            if loc.path == self.path
            else f"{comment_safe(loc.path, 60)} line {loc.line}"
        )
        self.emit(f"# {where}: {comment_safe(text)}".rstrip())

    def region(self, kind: str, node: Any) -> int:
        self.n += 1
        loc = getattr(node, "loc", None) or Location(self.path, 0, 0)
        fname = self.fn.sym.name if self.fn else ""
        self.regions[self.n] = (kind, fname, loc.path, loc.line)
        return self.n

    # -- names ---------------------------------------------------------------------------------
    def var_name(self, sym: Symbol, node: Any) -> str:
        if sym.kind in ("local", "param"):
            name = "v_" + python_ident(sym.unique_name or sym.name, node)
            if self.fn is not None:
                self.fn.local_syms[name] = sym
            return name
        if sym.kind == "global" and sym.qualifier == "uniform" and self._fed(sym):
            self.uniforms.add(sym.name)  # a plain file's own `uniform vec3 iResolution;`
            return "S.u_" + sym.name
        if sym.kind == "global":
            if sym.type.contains_opaque:
                raise _error(
                    f"'{sym.name}': textures are not supported by the NumPy backend yet",
                    node,
                    help="render with --backend gl",
                )
            return "S.g_" + python_ident(sym.unique_name or sym.name, node)
        if sym.kind == "uniform":
            from ....shadertoy.wrapper import UNIFORMS_BY_NAME

            u = UNIFORMS_BY_NAME.get(sym.name)
            if u is None:
                raise _error(f"unknown uniform '{sym.name}'", node)
            if u.glsl_type.startswith("sampler") and u.glsl_type != "sampler2D":
                raise _error(
                    f"'{sym.name}': {u.glsl_type} is not supported by the NumPy backend yet",
                    node,
                    help="render with --backend gl",
                )
            self.uniforms.add(sym.name)  # a sampler's value: a channels.ChannelInput (textures.py)
            return "S.u_" + sym.name
        if sym.kind == "builtin-var":
            if sym.name == "gl_FragCoord":
                return "S.frag_coord4"
            if sym.name == "gl_FrontFacing":
                return self.const_bool(True)
            if sym.const_value is not None and isinstance(sym.const_value, int):
                return self.const_int(sym.const_value, False)
            raise _error(f"'{sym.name}' is not supported by the NumPy backend", node)
        raise _error(f"'{sym.name}' ({sym.kind}) cannot be used as a value here", node)

    def fn_name(self, sym: Symbol) -> str:
        key = id(sym)
        if key not in self.fn_names:
            self.fn_names[key] = "f_" + python_ident(sym.unique_name or sym.name, sym.node)
        return self.fn_names[key]

    def struct_name(self, st: Any) -> str:
        key = id(st)
        if key not in self.struct_names:
            name = st.name if IDENT.match(st.name or "") else f"anon{len(self.struct_names)}"
            names = set(self.struct_names.values())
            base, i = "s_" + name, 1
            cand = base
            while cand in names:
                i += 1
                cand = f"{base}_{i}"
            self.struct_names[key] = cand
        return self.struct_names[key]

    @staticmethod
    def member(name: str, node: Any) -> str:
        return "m_" + python_ident(name, node)

    # -- constants and zero values -------------------------------------------------------------
    def const_float(self, v: float, v32: float | None = None) -> str:
        """The module constant of the float `v`; `v32`, a literal's float32 when rounding `v`
        (its float64) to float32 does not give it (a decimal just off a float32 halfway point),
        is what the constant holds in float32."""
        import math

        from ....semantics.consteval import f32

        if math.isnan(v):
            text, lit = "nan", "1e999 - 1e999"  # never produced by a literal; kept for folds
        elif math.isinf(v):
            text, lit = ("inf" if v > 0 else "minf"), ("1e999" if v > 0 else "-1e999")
        else:
            lit = repr(float(v))
            text = lit.replace("-", "m").replace("+", "").replace(".", "p")
        name = "C_f_" + text
        if v32 is not None and not math.isinf(v) and v32 != f32(v):
            name += "_f32_" + repr(v32).replace("-", "m").replace("+", "").replace(".", "p")
            lit += f", {v32!r}" if not math.isinf(v32) else (", 1e999" if v32 > 0 else ", -1e999")
        self.consts.setdefault(name, f"rt.const_float({lit})")
        self.float_consts[name] = float(v)
        return name

    def const_int(self, v: int, unsigned: bool) -> str:
        v = int(v)
        if unsigned:
            v &= 0xFFFFFFFF
            name = f"C_u_{v}"
            self.consts.setdefault(name, f"rt.const_uint({v})")
        else:
            v = (v + 2**31) % 2**32 - 2**31
            name = f"C_i_{v}".replace("-", "m")
            self.consts.setdefault(name, f"rt.const_int({v})")
        return name

    def const_bool(self, v: bool) -> str:
        name = "C_b_" + ("true" if v else "false")
        self.consts.setdefault(name, f"rt.const_bool({bool(v)})")
        return name

    def shape_of(self, t: Any, node: Any) -> tuple[tuple[int, ...], str]:
        if t.is_array:
            inner, kind = self.shape_of(t.element, node)
            return (t.array_size,) + inner, kind
        if t.is_scalar:
            return (), t.base
        if t.is_vector:
            return (t.size,), t.base
        if t.is_matrix:
            return (t.cols, t.rows), "float"
        raise _error(f"values of type '{t}' are not supported by the NumPy backend", node)

    def initial(self, t: Any, node: Any, mask: str | None = None) -> str:
        """The value a variable declared without one starts with (an out parameter, a local
        without an initializer): zero, as WebGL; an undefined read's variable in the "vary"
        mode draws a value (`X.undefined`)."""
        if id(node) in self.undefined_origins:
            return f"X.undefined(S, {self.zero(t, node)})"
        return self.zero(t, node)

    def zero(self, t: Any, node: Any, lead: tuple[int, ...] = ()) -> str:
        """The name of a module constant holding the zero value of type t (with leading array
        axes)."""
        if t.is_array and (t.element.is_struct or lead):
            return self.zero(t.element, node, lead + (t.array_size,))
        if t.is_struct:
            sname = self.struct_name(t)
            key = "Z_" + sname + "".join(f"_a{n}" for n in lead)
            if key not in self.zero_defs:
                fields = ", ".join(
                    f"{self.member(fname, node)}={self.zero(ft, node, lead)}"
                    for fname, ft in t.fields
                )
                self.zero_defs[key] = f'rt.struct("{sname}", {fields})'
            return key
        shape, kind = self.shape_of(t, node)
        shape = lead + shape
        key = f"Z_{kind}" + "".join(f"_{n}" for n in shape)
        self.zero_defs.setdefault(key, f'rt.zeros({shape!r}, "{kind}")')
        return key
