"""Python's limits: generated code that CPython can always compile, and the per-lane state
estimate the renderer sizes its tiles by."""

from __future__ import annotations

import re
from typing import Any

from ....base.diagnostics import Diagnostic, GlslError, Location
from ....frontend import syntax as A
from ...cpu_core.common import TRANSPILE_RULE, comment_safe, fold_tree
from .common import _ASSIGNED, _LOCAL_REF, OUTLINE_LOOPS, SPILL_HEIGHT
from .state import TranspilerState

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from ....semantics.model import Model


class PythonLimits(TranspilerState):
    """What keeps the generated code inside CPython's limits, whatever the GLSL's nesting:

    * an expression node SPILL_HEIGHT syntax levels high (or a multiple of it) is computed into a
      temporary, so no printed expression nests more than about 2 * SPILL_HEIGHT brackets (the
      tokenizer allows 200). Earlier operands of such an expression go to temporaries first
      (`needs_hoist`), so the evaluation order is kept;
    * a statement that would start OUTLINE_INDENT levels deep, or inside OUTLINE_LOOPS Python
      loops of one function (CPython allows 100 levels and 20 loops), is emitted as a
      module-level helper `h_<function>_<n>(S, locals...)` that returns the locals it may
      change; the caller rebinds them. An expression that would start OUTLINE_EXPR_INDENT deep
      (nested `&&`, ternaries with side effects) is outlined the same way, returning its value;
    * the transpiler's own recursion is given room as the checker's is, and the generated module
      is compiled once before it is handed out: whatever still fails (a limit this scheme does
      not foresee) is a located "too complex to render on the CPU" error, not a traceback.

    Mixed into `Transpiler` (it provides `lines`, `indent`, `fn`, `emit`, `tmp`, `fresh`)."""

    def local_names(self, lines: list[str]) -> set[str]:
        """The local names (`v_...`, `_...`) the code of these generated lines mentions. Each
        line is scanned once (`_line_names`): regions nested hundreds deep ask it of the same
        lines again and again."""
        out: set[str] = set()
        cache = self._line_names
        for ln in lines:
            names = cache.get(ln)
            if names is None:
                names = cache[ln] = frozenset(
                    m.group(1) for m in _LOCAL_REF.finditer(ln.split("#", 1)[0])
                )
            out |= names
        return out

    def _height(self, e: Any) -> int:
        return fold_tree(e, self._heights, lambda n, kids: 1 + max(kids, default=0))

    def spill(self, e: Any, text: str) -> str:
        """`text` (the printed `e`), or a temporary holding it when e is SPILL_HEIGHT * k high."""
        h = self._height(e)
        if h >= SPILL_HEIGHT and h % SPILL_HEIGHT == 0 and self.fn is not None:
            return self.tmp(text)
        return text

    def too_deep(self, limit: int, loops: bool = True) -> bool:
        fs = self.fn
        return fs is not None and (self.indent >= limit or (loops and fs.blocks >= OUTLINE_LOOPS))

    def outline(self, build, node: Any) -> str | None:
        """Emit what `build()` emits (and its value, if it returns one) in a new module-level
        function of the locals it reads; emit the call here and return the value's name."""
        fs = self.fn
        assert fs is not None  # generating a function's body
        defined = set(fs.defined)
        saved = self.lines, self.indent, fs.nest, fs.blocks, self.cse
        # (no common subexpressions shared with the caller: temporaries here are the function's)
        self.lines, self.indent, fs.nest, fs.blocks, self.last_line, self.cse = (
            [],
            1,
            0,
            0,
            None,
            None,
        )
        try:
            value = build()
            if value is not None:
                value = self.tmp(value)
            body = self.lines
        finally:
            self.lines, self.indent, fs.nest, fs.blocks, self.cse = saved
            self.last_line = None
        used = sorted(self.local_names(body) & defined)
        # the locals it may rebind: every name left of an `=` (more than needed is harmless)
        targets = {
            m.group(1)
            for ln in body
            for t in _ASSIGNED.findall(ln.split("#", 1)[0].strip())
            for m in _LOCAL_REF.finditer(t)
        }
        out = ([value] if value is not None and value in fs.defined else []) + [
            u for u in used if u in targets
        ]
        self.n += 1
        sym = fs.sym
        base = self.fn_name(sym)[2:] if getattr(sym, "kind", None) == "function" else "globals"
        name = f"h_{base}_{self.n}"
        loc = getattr(node, "loc", None)
        where = f" line {loc.line}" if loc is not None and loc.line else ""
        self.helpers.append(
            "\n".join(
                [
                    f"def {name}({', '.join(['S'] + used)}):",
                    f'    """Part of {comment_safe(sym.name, 60)}{where}, '
                    "a function of its own to stay within"
                    ' Python\'s nesting limits."""',
                ]
                + body
                + [f"    return ({''.join(o + ', ' for o in out)})", ""]
            )
        )
        call = f"{name}({', '.join(['S'] + used)})"
        self.emit(f"{''.join(o + ', ' for o in out)}= {call}" if out else call)
        return value


def _scalars(t: Any) -> int:
    """Scalars in one lane's value of type t."""
    if t.is_array:
        return (t.array_size or 0) * _scalars(t.element)
    if t.is_struct:
        return sum(_scalars(ft) for _, ft in t.fields)
    if t.is_matrix:
        return t.cols * t.rows
    return t.size if t.is_vector else 1


def lane_state(model: Model, functions: list[Any]) -> tuple[int, Any]:
    """(an estimate of the scalars one lane holds at once, the declaration of the largest
    variable): every variable of every function (as if all were alive together), two more
    copies of the largest one (a masked write to an array builds the new array beside the old)
    and 256 scalars of temporaries."""
    nodes = [g.node for g in model.globals if g.kind == "global" and not g.type.contains_opaque]
    for fn in functions:
        nodes += fn.node.proto.params
        nodes += [
            n for n in fn.node.body.walk() if isinstance(n, (A.Declarator, A.ConditionDeclaration))
        ]
    total, largest, at = 0, 0, None
    for n in nodes:
        sym = model.symbol_of(n)
        if sym is None or sym.type.contains_opaque:
            continue
        k = _scalars(sym.type)
        total += k
        if k > largest:
            largest, at = k, n
    return total + 2 * largest + 256, at


def too_complex(message: str, loc: Any) -> GlslError:
    return GlslError(
        Diagnostic(
            f"this program is too complex to render on the CPU ({message})",
            loc,
            rule=TRANSPILE_RULE,
            help="simplify the nesting here, or render with --backend gl",
        )
    )


def glsl_location(source: str, lineno: int, path: str) -> Location:
    """The GLSL line of generated line `lineno`: the nearest `# line N` comment above it."""
    lines = source.splitlines()
    for text in reversed(lines[: max(lineno, 1)]):
        m = re.match(r"\s*# (?:(.*) )?line (\d+): ", text)
        if m and (m.group(1) is None or m.group(1) == comment_safe(path, 60)):
            return Location(path, int(m.group(2)), 1)
    return Location(path, 1, 1)


def compile_generated(source: str, filename: str, path: str) -> Any:
    """The code object of a generated module; a located GlslError if Python cannot compile it."""
    try:
        return compile(source, filename, "exec")
    except (SyntaxError, RecursionError, MemoryError, ValueError) as e:
        lineno = getattr(e, "lineno", None) or 1
        msg = getattr(e, "msg", None) or str(e) or type(e).__name__
        raise too_complex(
            f"Python cannot compile the generated code: {msg}", glsl_location(source, lineno, path)
        ) from None
