"""Constants merged into the value a variable holds in each copy of a loop NIR unrolls, rendered
by llvmpipe and by both CPU engines bit for bit (nir_fold/loop_copies.py, loop_compounds.py).

NIR unrolls a loop of a constant count and a small body, then runs its algebraic rules on the
copies: a read of a variable at the top of the body is the value it had before the loop in the
first copy and the value of the body's last write in the others, and ``#a * (b * #c) -> (a*c) *
b`` (``#a + (b + #c) -> (a + c) + b``) merges a constant at the read into it. The induction
variable is a constant in each copy, so ``p.y * float(i) * 1.01`` is ``p.y * (float(i)*1.01)``.

Each shape is a loop `PASSES` passes long; three renders of the driver tell what it computes:
the loop as written (unrolled), the same loop run ``PASSES + iFrame`` times (iFrame is 0: the
same passes, a loop NIR keeps, whose top is a phi: the written order), and Mesa's order spelled
out in GLSL (the constants in parentheses, folded in float32 by the compiler). The unrolled loop
equals Mesa's order on every pixel, and the kept loop differs from it (the shape tells the two
orders apart). Measured on llvmpipe of Mesa 22.3 (160x90, 14,400 pixels), the pixels where
the NumPy backend and the compiled engine (the same on both) differed from the unrolled loop
before they copied the rule: ``a = p.y * 0.013`` then ``a = sin(a * 1.01)`` once 4,320, four
times 3,360; ``sin(a * 1.01) * 0.7`` three times 8,960 (the first copy and the later ones
merge); the sums 160 and 4,800, the differences 5,440; ``a *= 1.01`` and ``a += 1.01`` in the
body 3,680 and 160; a vec2 12,224; ``a * float(i) * 1.01`` 4,960, ``p.y * float(i) * 1.01``
8,640, ``p.y + float(i) + 1.01`` 5,440, with a break in the body 7,840; the body written out
without a loop 160 to 4,744. Not copied: a write of one component (``a.x = sin(a.x - 1.01) -
0.7``: components.py's, 5,440 pixels), chains of ``*=`` through the copies (measured only for
the value before the loop), and in a loop NIR keeps, the constant sunk past the loop's variable
(:func:`_kept`: 7,360 pixels of ``p.y * float(i) * 1.01``, 1,600 of the sum)."""

from __future__ import annotations

import pytest
from image_bits import assert_same, differing_pixels, render

W = "void mainImage(out vec4 c, in vec2 p) {\n%s\n    c = vec4(a, 0.0, 1.0);\n}"

# name -> (before the loop, the loop's body, passes, Mesa's order for them: the whole text)
SHAPES = {
    "one_pass": (
        "float b = p.y * 0.013;",
        "b = sin(b * 1.01);",
        1,
        "float b = sin(p.y * (0.013 * 1.01));",
    ),
    "first_copy": (
        "float b = p.y * 0.013;",
        "b = sin(b * 1.01);",
        4,
        "float b = sin(p.y * (0.013 * 1.01));" + " b = sin(b * 1.01);" * 3,
    ),
    "every_copy": (
        "float b = p.y * 0.013;",
        "b = sin(b * 1.01) * 0.7;",
        3,
        "float b = sin(p.y * (0.013 * 1.01)); b = sin(b * (0.7 * 1.01));"
        " b = sin(b * (0.7 * 1.01)) * 0.7;",
    ),
    "sum_first_copy": (
        "float b = p.y + 0.013;",
        "b = sin(b + 1.01);",
        3,
        "float b = sin(p.y + (0.013 + 1.01)); b = sin(b + 1.01); b = sin(b + 1.01);",
    ),
    "sum_every_copy": (
        "float b = p.y + 0.013;",
        "b = sin(b + 1.01) + 0.7;",
        3,
        "float b = sin(p.y + (0.013 + 1.01)); b = sin(b + (0.7 + 1.01));"
        " b = sin(b + (0.7 + 1.01)) + 0.7;",
    ),
    "difference_every_copy": (
        "float b = p.y - 0.013;",
        "b = sin(b - 1.01) - 0.7;",
        3,
        "float b = sin(p.y - (0.013 + 1.01)); b = sin(b - (0.7 + 1.01));"
        " b = sin(b - (0.7 + 1.01)) - 0.7;",
    ),
    "times_assign": (
        "float b = p.y * 0.013;",
        "b *= 1.01; b = sin(b);",
        3,
        "float b = sin(p.y * (0.013 * 1.01)); b = sin(b * 1.01); b = sin(b * 1.01);",
    ),
    "plus_assign": (
        "float b = p.y + 0.013;",
        "b += 1.01; b = sin(b);",
        3,
        "float b = sin(p.y + (0.013 + 1.01)); b = sin(b + 1.01); b = sin(b + 1.01);",
    ),
    "vector": (
        "vec2 a = p * 0.013;",
        "a = sin(a * 1.01) * 0.7;",
        3,
        "vec2 a = sin(p * (0.013 * 1.01)); a = sin(a * (0.7 * 1.01));"
        " a = sin(a * (0.7 * 1.01)) * 0.7;",
    ),
    "induction_times_copy": (
        "float b = p.y * 0.013;",
        "b = sin(b * float(i) * 1.01);",
        (1, 4),
        "float b = sin(p.y * (0.013 * 1.01)); b = sin(b * (2.0 * 1.01));"
        " b = sin(b * (3.0 * 1.01));",
    ),
    "induction_product": (
        "float b = 0.0;",
        "b += sin(p.y * float(i) * 1.01);",
        (3, 6),
        "float b = 0.0; b += sin(p.y * (3.0 * 1.01)); b += sin(p.y * (4.0 * 1.01));"
        " b += sin(p.y * (5.0 * 1.01));",
    ),
    "induction_sum": (
        "float b = 0.0;",
        "b += sin(p.y + float(i) + 1.01);",
        (3, 6),
        "float b = 0.0; b += sin(p.y + (3.0 + 1.01)); b += sin(p.y + (4.0 + 1.01));"
        " b += sin(p.y + (5.0 + 1.01));",
    ),
    "induction_with_a_break": (
        "float b = 0.0;",
        "b += sin(p.y * float(i) * 1.01); if (b > 1.5) break;",
        (3, 6),
        "float b = 0.0; for (int i = 3; i < 6; i++) {"
        " b += sin(p.y * (float(i) * 1.01)); if (b > 1.5) break; }",
    ),
}


def _loop(name: str, kept: bool) -> str:
    before, body, passes, _ = SHAPES[name]
    start, end = passes if isinstance(passes, tuple) else (0, passes)
    count = f"{end} + iFrame" if kept else str(end)
    text = f"{before} for (int i = {start}; i < {count}; i++) {{ {body} }}"
    return W % (text + _result(before))


def _straight(name: str) -> str | None:
    """The body written out `passes` times, no loop (None for a body that reads the loop's
    variable or leaves it): NIR's SSA sees the same values as in the unrolled copies."""
    before, body, passes, _ = SHAPES[name]
    if isinstance(passes, tuple):
        return None
    return W % (before + f" {body}" * passes + _result(before))


def _result(text: str) -> str:
    return "" if text.startswith("vec2 a") else " vec2 a = vec2(b, 0.0);"


def _mesa(name: str) -> str:
    text = SHAPES[name][3]
    return W % (text + _result(text))


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_llvmpipe_merges_the_constants_in_the_copies_of_an_unrolled_loop(
    llvmpipe, make_shader, name
):
    """The unrolled loop (and the body written out as often) is Mesa's order on every pixel;
    the loop NIR keeps is not (else the shape could not tell the orders apart)."""
    unrolled = render(make_shader(_loop(name, kept=False)), "gl", frame=0)
    mesa = render(make_shader(_mesa(name)), "gl", frame=0)
    kept = render(make_shader(_loop(name, kept=True)), "gl", frame=0)
    what = f"{name} on llvmpipe at 160x90, iFrame 0"
    assert_same(unrolled, mesa, what=what, names=("the unrolled loop", "Mesa's order"))
    assert differing_pixels(kept, mesa) > 0, name
    straight = _straight(name)
    if straight is not None:
        straight_image = render(make_shader(straight), "gl", frame=0)
        assert_same(straight_image, mesa, what=what, names=("the body written out", "Mesa's order"))


def _kept(name: str) -> str | None:
    """The loop NIR keeps, for the shapes whose written order the engines copy: not those that
    read the loop's variable (NIR sinks the constant past it there, ``(p.y * float(i)) * 1.01``
    is ``(p.y * 1.01) * float(i)``: sink.py does not take ``float(i)`` for a value no rule
    looks into)."""
    return None if isinstance(SHAPES[name][2], tuple) else _loop(name, kept=True)


FORMS = {
    "unrolled": lambda name: _loop(name, kept=False),
    "kept": _kept,
    "straight": _straight,
}
CASES = [(n, f) for n in sorted(SHAPES) for f in FORMS if FORMS[f](n) is not None]


@pytest.mark.parametrize("backend", ["numpy", "compiled"])
@pytest.mark.parametrize("name, form", CASES, ids=[f"{n}-{f}" for n, f in CASES])
def test_engines_merge_the_constants_in_the_copies_as_llvmpipe(
    renders_as_llvmpipe, make_shader, name, form, backend
):
    """Both CPU engines render the unrolled loop, the kept one and the body written out as the
    driver does."""
    renders_as_llvmpipe(make_shader(FORMS[form](name)), backend, name=f"{name}, {form}", frame=0)
