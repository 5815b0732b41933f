"""The help a type error offers, and where an error about a declaration or a call points.

Pure helpers of the semantic pass: the literal to write instead of an int where a float is
needed, the conversion to write between types of one size, and `NameAt`, the location of a
declared or called name, computed only when an error is reported.
"""

from __future__ import annotations

from ...base.diagnostics import Location
from ...frontend import syntax as A
from ...language import glsl_types as T

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Any


def int_literal_hint(node: A.Node) -> str | None:
    """'write 1.0' for an int literal (possibly negated) where a float is needed."""
    if isinstance(node, A.IntLiteral) and not node.unsigned:
        return f"write {node.value}.0"
    if isinstance(node, A.Unary) and node.op == "-" and isinstance(node.operand, A.IntLiteral):
        return f"write -{node.operand.value}.0"
    return None


def conversion_help(want: T.Type, got: T.Type) -> str | None:
    """'convert it: vec3(...)' between basic types of the same size."""
    if want.is_basic and got.is_basic and want.size == got.size:
        return f"convert it: {want}(...)"
    return None


class NameAt:
    """Where an error about a declaration or a call points: its name (`name_loc`, a call's
    `callee_loc`), else the whole node. Found only when an error is reported: reading the name's
    location computes it (base/diagnostics.py's pending locations), and most nodes have no error."""

    __slots__ = ("node", "field")

    def __init__(self, node: Any, field: str = "name_loc") -> None:
        self.node = node
        self.field = field

    @property
    def loc(self) -> Location:
        name_loc = getattr(self.node, self.field)
        return name_loc if name_loc.line else self.node.loc
