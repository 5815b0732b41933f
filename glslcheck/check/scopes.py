"""Lexical scopes of GLSL ES 3.00 (spec 4.2): global, function (parameters), block, for-init
and while-condition scopes, and the program-wide unique names the NumPy transpiler uses.

A `Scope` maps names to `Symbol`s and knows its parent. Variables, structs and functions share
one namespace per scope (spec 4.2.7); a function's overloads are kept on the model, the scope
holds the first one. `UniqueNames` hands out `x`, `x_1`, `x_2`, ... avoiding every name the
user wrote, so a renamed shadowing variable never collides with a real one.
"""

from __future__ import annotations

from .model import Symbol


class Scope:
    def __init__(self, parent: "Scope | None", kind: str) -> None:
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
    def __init__(self, taken: set[str]) -> None:
        self.taken = set(taken)
        self.given: set[str] = set()
        self.next: dict[str, int] = {}  # the next suffix to try per name: linear, not quadratic

    def make(self, name: str) -> str:
        if name not in self.given:
            self.given.add(name)
            return name
        i = self.next.get(name, 1)
        while f"{name}_{i}" in self.taken or f"{name}_{i}" in self.given:
            i += 1
        self.next[name] = i + 1
        unique = f"{name}_{i}"
        self.given.add(unique)
        return unique
