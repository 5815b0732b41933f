"""The transpiler's state: the function being generated (`FnState`, its `LoopCtx`s), an
l-value (`LValue`), and `TranspilerState`, the base of every part of the transpiler.

`Transpiler` (module.py) is made of one class per concern (names, functions, statements,
expressions, Python's limits); each part reads the state `Transpiler.__init__` sets up and calls
methods another part defines. `TranspilerState` declares both for type checkers, so each part is
checked on its own against them (and mypy checks each definition against its declaration). At
run time it is an empty class. (This module imports none of the parts: they all import it.)
"""

from __future__ import annotations

from dataclasses import dataclass, field

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any

    from ....frontend import syntax as A
    from ....semantics.analysis import UndefinedRead
    from ....semantics.model import Model, Symbol
    from ...cpu_core.facts import Facts, SideEffects
    from ...cpu_core.fold_state import FoldState
    from ...cpu_core.uniformity import Uniformity


@dataclass
class LoopCtx:
    kind: str  # "loop" | "switch"
    live: str
    cont: str | None = None


class FnState:
    def __init__(self, sym: Symbol, uni: Uniformity | None, is_entry: bool) -> None:
        self.sym = sym
        self.uni = uni  # None for the global initializers (gen_globals)
        self.is_entry = is_entry
        self.defined: list[str] = []  # Python locals bound so far, in order
        self.local_syms: dict[str, Symbol] = {}  # Python name -> its local or parameter
        self.loops: list[LoopCtx] = []
        self.has_ret = False
        self.rv: str | None = None
        self.outs: list[str] = []
        self.switch_depth = 0
        self.no_compact = 0
        self.nest = 0
        self.blocks = 0  # Python loops around the current line, in this Python function
        self.switch_locals: set[str] = set()  # declared in a switch body: bound before the switch


@dataclass
class LValue:
    """An l-value with its index expressions already evaluated: base name and an access path.
    path items: ("field", "m_name") | ("swz", (i, j, ...)) | ("index", "expr", type_of_base)."""

    base: str
    base_type: Any
    path: list[tuple] = field(default_factory=list)
    free: bool = (
        False  # written without a mask (`Uniformity.is_free`: no lane left out reads it again)
    )


class TranspilerState:
    if TYPE_CHECKING:
        # Set up by Transpiler.__init__ (see there).
        COMPACT_MIN_NODES: int
        keep_alpha: bool
        undefined: str  # what undefined reads see: "zero" (WebGL's) or "vary"
        # id(origin node) -> its undefined read, for the origins "vary" draws a value for
        undefined_origins: dict[int, UndefinedRead]
        model: Model
        path: str
        entry: Any
        functions: list[Any]
        facts: Facts
        fold_state: FoldState
        lines: list[str]
        consts: dict[str, str]
        float_consts: dict[str, float]
        const_exprs: dict[str, str]
        in_const: bool
        zero_defs: dict[str, str]
        fn_names: dict[int, str]
        struct_names: dict[int, str]
        n: int
        regions: dict[int, tuple[str, str, str, int]]
        loops: dict[int, tuple[str, int, int]]
        fn: FnState | None  # the function being generated
        indent: int
        last_line: tuple[str, int] | None
        plain: bool
        uniforms: set[str]
        helpers: list[str]
        _heights: dict[int, int]
        side_effects: SideEffects
        _hoists: dict[int, bool]
        _derivs: dict[int, bool]
        _line_names: dict[str, frozenset]
        dead_lane_reads: dict[int, dict[int, int]]
        cse: tuple[set[int], dict[str, str]] | None
        # The tracing transpiler's expressions to report (tracing.py), else None.
        watched: dict[int, tuple[str, Any, str]] | None

        # Names (names.py)
        def emit(self, text: str) -> None: ...
        def fresh(self, prefix: str) -> str: ...
        def comment_line(self, node: Any) -> None: ...
        def region(self, kind: str, node: Any) -> int: ...
        def var_name(self, sym: Symbol, node: Any) -> str: ...
        def fn_name(self, sym: Symbol) -> str: ...
        def struct_name(self, st: Any) -> str: ...
        @staticmethod
        def member(name: str, node: Any) -> str: ...
        def const_float(self, v: float, v32: float | None = None) -> str: ...
        def const_int(self, v: int, unsigned: bool) -> str: ...
        def const_bool(self, v: bool) -> str: ...
        def initial(self, t: Any, node: Any, mask: str | None = None) -> str: ...
        def zero(self, t: Any, node: Any, lead: tuple[int, ...] = ()) -> str: ...

        # Functions (functions.py)
        def final_return(self, value: str | None = None) -> str: ...
        def user_call(self, e: A.Call, fn: Symbol, mask: str | None) -> str: ...
        @staticmethod
        def _fed(sym: Symbol) -> bool: ...

        # Statements (statements.py)
        def block(self, stmts: list[Any], mask: str | None, top: bool = False) -> bool: ...
        def assign_stmt(self, target: str, value: str, mask: str | None) -> None: ...
        def _worth_compacting(self, node: Any) -> bool: ...
        def effect(self, e: Any, mask: str | None, step_unmasked: bool = False) -> None: ...

        # Expressions (expressions.py)
        def expr(self, e: Any, mask: str | None) -> str: ...
        def has_effects(self, e: Any) -> bool: ...
        def tmp(self, value: str) -> str: ...
        def incdec(self, e: Any, mask: str | None, want_value: bool) -> str: ...
        def assignment(self, e: A.Assignment, mask: str | None, want_value: bool) -> str: ...
        def lvalue(self, e: Any, mask: str | None) -> LValue: ...
        def read(self, lv: LValue, upto: int | None = None) -> str: ...
        def write(self, lv: LValue, value: str, mask: str | None) -> None: ...
        def type_of(self, e: Any) -> Any: ...
        def exprs(self, items: list[Any], mask: str | None) -> list[str]: ...
        def binary_values(self, op: str, lt: Any, rtp: Any, left: str, right: str) -> str: ...
        def ieee(self, op: str, left: str, right: str) -> str: ...
        def negate(self, value: str) -> str: ...
        def llvmpipe(self, rewritten: str, written: str) -> str: ...
        def by_copy(self, loop: Any, first: str, later: str) -> str: ...
        def store(self, target: str, value: str) -> str: ...
        @staticmethod
        def component(value: str, i: int) -> str: ...
        @staticmethod
        def runtime(name: str, *args: str) -> str: ...
        @staticmethod
        def vector(parts: list[str]) -> str: ...
        @staticmethod
        def leaves(value: str, t: Any) -> list[str]: ...
        @staticmethod
        def swizzle(value: str, idx: tuple[int, ...]) -> str: ...

        # PythonLimits (limits.py)
        def local_names(self, lines: list[str]) -> set[str]: ...
        def _height(self, e: Any) -> int: ...
        def spill(self, e: Any, text: str) -> str: ...
        def too_deep(self, limit: int, loops: bool = True) -> bool: ...
        def outline(self, build: Callable[[], str | None], node: Any) -> str | None: ...
