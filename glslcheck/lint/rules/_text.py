"""Text helpers the lint rules share for messages and suggested rewrites (not a rule: no NAME,
not in the table). The analysis they report on lives in glslcheck/analysis."""

from __future__ import annotations

from typing import Any

from ... import ast as A
from ...analysis import numbers
from ...check.model import Model
from ...printer import to_glsl

COMPARISONS = ("<", "<=", ">", ">=")
FLIPPED = {"<": ">", "<=": ">=", ">": "<", ">=": "<="}  # a op b  <=>  b FLIPPED[op] a


def text(e: Any) -> str:
    """GLSL text of an expression, shortened for a message."""
    s = to_glsl(e)
    return s if len(s) <= 60 else s[:57] + "..."


def is_atom(e: Any) -> bool:
    """A name, a literal, or a field/swizzle/element of one: printed inside a larger expression
    it needs no parentheses. (Not the NumPy transpiler's `is_plain_read`, which asks whether a value
    is read without computing anything per lane.)"""
    while type(e) in (A.Field, A.Index):
        e = e.base
    return type(e) in (A.Identifier, A.FloatLiteral, A.IntLiteral, A.BoolLiteral)


def wrap(e: Any) -> str:
    """GLSL text of `e`, in parentheses unless it is an atom or a call."""
    return text(e) if is_atom(e) or type(e) is A.Call else f"({text(e)})"


def squared(model: Model, e: Any) -> str:
    """`r * r` for an expression, or the folded square of a constant bound."""
    nums = numbers(model.const_value(e))
    if len(nums) == 1:
        v = nums[0] * nums[0]
        s = repr(v) if v != int(v) or abs(v) >= 1e16 else f"{int(v)}.0"
        return s if len(s) < 12 else f"{v:g}"
    w = wrap(e)
    return f"{w} * {w}"
