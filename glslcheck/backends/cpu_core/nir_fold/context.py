"""What nir_fold's decisions read of the engine that asks them, for an engine that is not the NumPy
transpiler.

The rules take the NumPy Transpiler (`tr`) and read of it the program (`model`, `facts`), the
function being emitted (`fn`: its `sym` and `is_entry`), their memo (`fold_state`), `type_of`
and `has_effects`; the rewrites also emit code through it. The compiled engine shares two
decisions with the NumPy backend that emit nothing, nir_lower_flrp's formula for a `mix`
(flrp.mix_form) and the test of an added constant zero (added_zero.zero_add): it asks them of
a :class:`FoldContext`, which holds just what they read."""

from __future__ import annotations

from typing import Any

from ..facts import Facts, SideEffects
from ..fold_state import FoldState

TYPE_CHECKING = False  # not typing's: importing typing costs every start-up
if TYPE_CHECKING:
    from typing import Self

    from ....semantics.model import Model, Symbol


class EmittedFunction:
    """The function the decisions are asked for (what they read of the transpiler's `tr.fn`)."""

    def __init__(self, sym: Symbol | None, is_entry: bool) -> None:  # (None: the globals)
        self.sym, self.is_entry = sym, is_entry


class FoldContext:
    """The program, its facts and the rules' memo, at one function (:meth:`at`) at a time."""

    def __init__(self, model: Model, facts: Facts) -> None:
        self.model = model
        self.facts = facts
        self.fold_state = FoldState()
        self.has_effects = SideEffects(model)
        self.fn: EmittedFunction | None = None

    def at(self, sym: Symbol | None, is_entry: bool) -> Self:
        """This context, at the function `sym`."""
        if self.fn is None or self.fn.sym is not sym:
            self.fn = EmittedFunction(sym, is_entry)
        return self

    def type_of(self, e: Any) -> Any:
        return self.model.type_of(e)

    @property
    def lines(self) -> Any:
        """The function being emitted, which a value a rule keeps belongs to (none here)."""
        return None
