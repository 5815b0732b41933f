"""Lexical scopes of GLSL ES 3.00 (spec 4.2): global, function (parameters), block, for-init
and while-condition scopes, and the program-wide unique names the NumPy transpiler uses.

A `Scope` maps names to `Symbol`s and knows its parent. Variables, structs and functions share
one namespace per scope (spec 4.2.7); a function's overloads are kept on the model, the scope
holds the first one. `UniqueNames` hands out `x`, `x_1`, `x_2`, ... avoiding every name the
user wrote, so a renamed shadowing variable never collides with a real one.
"""

from __future__ import annotations

from .model import Symbol

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from collections.abc import Callable


class Scope:
    def __init__(self, parent: Scope | None, kind: str) -> None:
        self.parent = parent
        self.kind = kind  # "builtin", "global", "function", "block", "for", "while", "switch"
        self.names: dict[str, Symbol] = {}

    def lookup(self, name: str) -> Symbol | None:
        scope: Scope | None = self
        while scope is not None:
            sym = scope.names.get(name)
            if sym is not None:
                return sym
            scope = scope.parent
        return None

    def local(self, name: str) -> Symbol | None:
        return self.names.get(name)

    def visible_names(self) -> set[str]:
        out: set[str] = set()
        scope: Scope | None = self
        while scope is not None:
            out.update(scope.names)
            scope = scope.parent
        return out


class UniqueNames:
    """Unique names: a name as written the first time, then `name_1`, `name_2`, ... skipping the
    names `taken` (a set, or a function giving it: called at the first repeated name, as most
    programs never repeat one and finding every name walks the whole tree)."""

    def __init__(self, taken: set[str] | Callable[[], set[str]]) -> None:
        self._taken = taken if callable(taken) else set(taken)
        self.given: set[str] = set()
        self.next: dict[str, int] = {}  # the next suffix to try per name: linear, not quadratic

    @property
    def taken(self) -> set[str]:
        if callable(self._taken):
            self._taken = set(self._taken())
        return self._taken

    def make(self, name: str) -> str:
        if name not in self.given:
            self.given.add(name)
            return name
        i = self.next.get(name, 1)
        taken = self.taken
        while f"{name}_{i}" in taken or f"{name}_{i}" in self.given:
            i += 1
        self.next[name] = i + 1
        unique = f"{name}_{i}"
        self.given.add(unique)
        return unique
