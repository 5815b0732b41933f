"""A variable advanced by constants, ``seed += 0.1`` written several times (path tracers' random
numbers), rendered by llvmpipe and by the NumPy backend bit for bit.

NIR is SSA: ``seed += 0.1; seed += 0.1; seed += 0.1`` is ``((s0 + 0.1) + 0.1) + 0.1``, and
nir_opt_algebraic's ``#a + (b + #c) -> (a + c) + b`` folds the constants into one in float32,
``s0 + K``, in the order nir_fold/sum_order.py simulates: right to left in a line of ``+=``
(its worklist visits the last addition first), left to right where a ``-=`` is involved (the
negation is a constant only a pass later), a loop of a constant count unrolled after the
body's constants were merged once. The rule stops at a phi: the top of a loop NIR keeps, the
join after a branch that writes the variable, the end of a loop that can be left early. Each
shader writes s0 (an opaque fract, 0 to 40) to the first channel;
:func:`test_llvmpipe_merges_the_constants_of_a_repeated_sum` compares the driver's other
channels with two orders computed here in NumPy float32 from that s0, Mesa's and another.

Measured on llvmpipe of Mesa 22.3 (160x90, 14,400 values a channel; the two orders differ on
the count in brackets): three ``+=`` match the merged order on 14,400 and the step-by-step one
on 298 (14,102); the second component of ``vec2(seed += 0.1, seed += 0.1)`` merged 14,400,
stepwise 7,812 (6,588); ``+=``, ``= seed +``, ``-=`` and ``+= 0.2`` mixed: merged 14,400,
stepwise 6,839; two ``+=`` in a loop body run twice (the merge restarts at each loop top):
merged per iteration 14,400, stepwise 7,524; a write inside an ``if`` then one after it (the
merge runs within the branch and stops at the join): 14,400 that way, 11,487 stepwise, 6,506
merged across the join; ``+= 0.047; += 1.802; -= 1.423``: left to right 14,400, right to left
11,320; ``+= 0.047; += 1.802; += 0.311`` read there: right to left 14,400, left to right
13,731. Through calls (inlined) and loops of constant count (unrolled): ``rnd(seed)`` (one
``+=``) three times merged 14,400, stepwise 298; ``hash2(seed)`` (a constructor of two) twice,
its last value merged 14,400, stepwise 162 (so a global seed advanced in ``ghash()``);
``rnd`` in the unrolled loop merged 14,400,
stepwise 162; two ``+=`` a pass, the body's sum first: 14,400, left to right 13,250; a
constant before the loop, added after the loop's own: 14,400, left to right 12,483; a loop
NIR keeps for the size of its body restarts the chain at every pass (16 passes of 17 lines of
3 instructions: 14,400 that way, 364 as if unrolled; of 16 lines: unrolled, 14,400). A global
passed to the ``inout`` parameter of ``hash2`` is merged as a local is (the parameter a copy of
it, copied back): one call, merged 14,400, stepwise 7,812; three calls 14,400 against 295; a
call in a function that passes the global, 162; a function writing ``gseed * 1.5`` between two
calls restarts the chain, 14,400 that way, 2,605 stepwise; the callee writing the global too
loses its write to the copy back (14,400 merged). A callee calling ``hash2`` in a loop NIR
keeps restarts the chain at every pass, 14,400 that way, 7,056 as one chain (7,038 for a
global). Writes in arms of an ``if`` (IN_ARMS): a callee advancing the seed in an arm after an
unrolled loop of its own merged 14,400, stepwise 303, the step after the call restarted at the
phi 14,400, continued 10,616; three passes of a loop calling a callee that writes in arms, the
first copy continuing the chain 14,400, restarting it 6,651. A call in each arm of the caller's
``if`` (CALLER_ARMS) continues the chain from before the ``if`` in both arms, 14,400 that way,
10,179 with the else arm restarting; a call in the else arm alone, 14,400 against 10,216.
Written for llvmpipe of Mesa 22.3 (the `llvmpipe` fixture skips elsewhere).
"""

from __future__ import annotations

import numpy as np
import pytest
from image_bits import SIZE, assert_same, render

HEAD = """float rnd(inout float seed) { seed += 0.1; return seed; }
vec2 hash2(inout float seed) { return vec2(seed += 0.1, seed += 0.1); }
float gseed;
vec2 ghash() { return vec2(gseed += 0.1, gseed += 0.1); }
vec2 shash(inout float seed) { return fract(sin(vec2(seed += 0.1, seed += 0.1)) * 43758.5453); }
vec2 hash2_reading(inout float seed) { float a = seed += 0.1; return vec2(a + gseed, seed += 0.1); }
vec2 hash2_aliased(inout float seed) {
    float a = seed += 0.1; gseed += 0.5; return vec2(a, seed += 0.1);
}
void scale() { gseed = gseed * 1.5; }
void arms(inout float seed, float s0) { if (s0 > 20.0) { hash2(seed); } else { rnd(seed); } }
void looped(inout float seed, float s0) {
    for (int i = 0; i < 2; i++) { rnd(seed); }
    if (s0 > 20.0) { hash2(seed); }
}
float returning(inout float seed, float s0) {
    if (s0 > 30.0) { hash2(seed); return 1.0; }
    if (s0 > 10.0) { rnd(seed); return 2.0; }
    hash2(seed);
    return 3.0;
}
float greturning(float s0) {
    if (s0 > 30.0) { ghash(); return 1.0; }
    if (s0 > 10.0) { gseed += 0.1; return 2.0; }
    ghash();
    return 3.0;
}
void bounce(inout float seed, float s0) {
    for (int j = 0; j < 3; j++) {
        if (j == 1 && s0 > 30.0) break;
        if (s0 > 20.0) { hash2(seed); } else { rnd(seed); }
    }
}
vec2 two() { hash2(gseed); return hash2(gseed); }
float walk(inout float seed) { for (int i = 0; i < iFrame + 2; i++) { hash2(seed); } return seed; }
void gwalk() { for (int i = 0; i < iFrame + 2; i++) { hash2(gseed); } }
void mainImage(out vec4 c, in vec2 p) {
    float s0 = fract(p.x * 0.1371 + p.y * 0.0917) * 40.0;
    float seed = s0;
"""
K, K2 = np.float32(0.1), np.float32(0.2)
P1 = np.float32(2.329)
R1, R2, R3 = np.float32(0.047), np.float32(1.802), np.float32(-1.423)
R4 = np.float32(0.311)


def _steps(s0, n):
    out = s0
    for _ in range(n):
        out = out + K
    return out


def _merged(s0, n):
    k = K
    for _ in range(n - 1):
        k = k + K
    return s0 + k


# name -> (body, {channel: (another order, Mesa's) as functions of s0})
SHAPES = {
    "three_additions": (
        "seed += 0.1; seed += 0.1; seed += 0.1;"
        " c = vec4(s0, seed, fract(sin(seed) * 43758.5453), 1.0);",
        {1: (lambda s: _steps(s, 3), lambda s: _merged(s, 3))},
    ),
    "constructor_with_side_effects": (
        "vec2 v = vec2(seed += 0.1, seed += 0.1);"
        " c = vec4(s0, v, fract(sin(dot(v, vec2(12.9898, 78.233))) * 43758.5453));",
        {2: (lambda s: _steps(s, 2), lambda s: _merged(s, 2))},
    ),
    "mixed_forms": (
        "seed += 0.1; seed = seed + 0.1; seed -= 0.1; seed += 0.2; c = vec4(s0, seed, 0.0, 1.0);",
        {1: (lambda s: (((s + K) + K) - K) + K2, lambda s: s + (((K + K) - K) + K2))},
    ),
    "constants_folded_left_to_right": (
        "seed += 0.047; seed += 1.802; seed -= 1.423; c = vec4(s0, seed, 0.0, 1.0);",
        {1: (lambda s: s + ((R3 + R2) + R1), lambda s: s + ((R1 + R2) + R3))},
    ),
    "constants_folded_right_to_left": (
        "seed += 0.047; seed += 1.802; seed += 0.311; float r = seed; seed += 2.719;"
        " c = vec4(s0, r, seed, 1.0);",
        {1: (lambda s: s + ((R1 + R2) + R4), lambda s: s + (R1 + (R2 + R4)))},
    ),
    "loop_body": (
        "for (int i = 0; i < iFrame + 2; i++) { seed += 0.1; seed += 0.1; }"
        " c = vec4(s0, seed, 0.0, 1.0);",
        {1: (lambda s: _steps(s, 4), lambda s: _merged(_merged(s, 2), 2))},
    ),
    "across_a_branch": (
        "seed += 0.1; if (s0 > 20.0) { seed += 0.1; } seed += 0.1; c = vec4(s0, seed, 0.0, 1.0);",
        {
            1: (
                lambda s: np.where(s > 20.0, _steps(s, 3), _steps(s, 2)),
                lambda s: np.where(s > 20.0, _merged(s, 2), _merged(s, 1)) + K,
            )
        },
    ),
}


# Mesa inlines every call and unrolls a loop of a constant count, so the chain runs through them
# (measured like SHAPES); the NumPy backend does not follow it there yet.
THROUGH_CALLS = {
    "three_calls": (
        "rnd(seed); rnd(seed); float r = rnd(seed); c = vec4(s0, r, 0.0, 1.0);",
        {1: (lambda s: _steps(s, 3), lambda s: _merged(s, 3))},
    ),
    "two_calls_with_a_constructor": (
        "vec2 a = hash2(seed); vec2 b = hash2(seed); c = vec4(s0, b.y, 0.0, 1.0);",
        {1: (lambda s: _steps(s, 4), lambda s: _merged(s, 4))},
    ),
    "a_global_through_calls": (
        "gseed = s0; ghash(); vec2 h = ghash(); c = vec4(s0, h.y, 0.0, 1.0);",
        {1: (lambda s: _steps(s, 4), lambda s: _merged(s, 4))},
    ),
    "a_global_passed_to_an_inout": (
        "gseed = s0; vec2 h = hash2(gseed); c = vec4(s0, h.y, gseed, 1.0);",
        {n: (lambda s: _steps(s, 2), lambda s: _merged(s, 2)) for n in (1, 2)},
    ),
    "a_global_passed_three_times": (
        "gseed = s0; hash2(gseed); hash2(gseed); vec2 h = hash2(gseed);"
        " c = vec4(s0, h.y, 0.0, 1.0);",
        {1: (lambda s: _steps(s, 6), lambda s: _merged(s, 6))},
    ),
    "a_global_passed_and_advanced_by_calls": (
        "gseed = s0; rnd(gseed); ghash(); vec2 h = hash2(gseed); c = vec4(s0, h.y, 0.0, 1.0);",
        {1: (lambda s: _steps(s, 5), lambda s: _merged(s, 5))},
    ),
    "a_global_passed_by_a_function": (
        "gseed = s0; vec2 h = two(); c = vec4(s0, h.y, gseed, 1.0);",
        {n: (lambda s: _steps(s, 4), lambda s: _merged(s, 4)) for n in (1, 2)},
    ),
    "a_global_read_between_calls": (
        "gseed = s0; hash2(gseed); float r = gseed; hash2(gseed); c = vec4(s0, r, gseed, 1.0);",
        {
            1: (lambda s: _steps(s, 2), lambda s: _merged(s, 2)),
            2: (lambda s: _steps(s, 4), lambda s: _merged(s, 4)),
        },
    ),
    "a_global_read_in_the_callee": (
        "gseed = s0; vec2 h = hash2_reading(gseed); c = vec4(s0, h.y, h.x, 1.0);",
        {1: (lambda s: _steps(s, 2), lambda s: _merged(s, 2))},
    ),
    "a_global_the_callee_writes_too": (
        "gseed = s0; vec2 h = hash2_aliased(gseed); c = vec4(s0, h.y, gseed, 1.0);",
        {n: (lambda s: _steps(s, 2), lambda s: _merged(s, 2)) for n in (1, 2)},
    ),
    "a_global_written_by_another_function": (
        "gseed = s0; hash2(gseed); scale(); vec2 h = hash2(gseed); c = vec4(s0, h.y, 0.0, 1.0);",
        {
            1: (
                lambda s: _steps(_steps(s, 2) * np.float32(1.5), 2),
                lambda s: _merged(_merged(s, 2) * np.float32(1.5), 2),
            )
        },
    ),
    "a_global_through_a_sin_hash": (
        "gseed = s0; vec2 h = shash(gseed); c = vec4(s0, gseed, h);",
        {1: (lambda s: _steps(s, 2), lambda s: _merged(s, 2))},
    ),
    "a_call_advancing_in_a_loop_kept": (
        "seed += 0.1; float r = walk(seed); c = vec4(s0, r, 0.0, 1.0);",
        {1: (lambda s: _merged(s, 5), lambda s: _restarted(s + K, [K, K], 2))},
    ),
    "a_global_advanced_in_a_loop_kept": (
        "gseed = s0; gwalk(); c = vec4(s0, gseed, 0.0, 1.0);",
        {1: (lambda s: _merged(s, 4), lambda s: _restarted(s, [K, K], 2))},
    ),
    "unrolled_loop": (
        "for (int i = 0; i < 4; i++) { rnd(seed); } c = vec4(s0, seed, 0.0, 1.0);",
        {1: (lambda s: _steps(s, 4), lambda s: _merged(s, 4))},
    ),
    "into_an_unrolled_loop": (
        "seed += 2.329; float r = 0.0; for (int i = 0; i < 4; i++) { r = rnd(seed); }"
        " c = vec4(s0, r, 0.0, 1.0);",
        {
            1: (
                lambda s: _left_to_right(s, [P1] + [K] * 4),
                lambda s: _unrolled(s, [P1], [K], 4, []),
            )
        },
    ),
}


# A call in a branch of a two-pass unrolled loop: where the branch's condition is a constant in
# the first copy, NIR folds that copy's branch away and the second copy's call continues its
# chain (then a phi); where it is not, both copies' calls follow a phi and restart the chain.
_BRANCHED = (
    "gseed = s0; float d = {start}; float n = 0.0;"
    " for (int i = 0; i < {passes}; i++) {{ if (d < 0.5) {{ vec2 h = ghash(); d = fract(h.y) * 0.1;"
    " n += 1.0; }} }} c = vec4(s0, gseed, n, 1.0);"
)
BRANCHED_CALLS = {
    "a_branch_folded_in_the_first_copy": (
        _BRANCHED.format(start="0.0", passes=2),
        {
            1: (
                lambda s: _restarted(s, [K, K], 2),
                lambda s: _unrolled(s, [], [K, K], 2, []),
            )
        },
    ),
    "a_branch_kept_in_the_first_copy": (
        _BRANCHED.format(start="fract(s0) * 0.1", passes=2),
        {
            1: (
                lambda s: _unrolled(s, [], [K, K], 2, []),
                lambda s: _restarted(s, [K, K], 2),
            )
        },
    ),
}
# A callee advancing its inout parameter only in a branch: inlined, the branch's additions
# continue the caller's chain (dominated by its last step), and a phi joins the branch.
BRANCHED_HEAD = """void maybe(inout float seed, float d) {
    if (d < 20.0) { seed += 0.1; seed += 0.1; }
}
vec2 hash2_if(inout float seed, float d) {
    vec2 h = vec2(d); if (d < 20.0) { h = hash2(seed); } return h;
}
"""
BRANCHED_CALLEES = {
    "a_callee_advancing_in_a_branch": (
        "seed += 0.1; maybe(seed, s0); float r = seed; seed += 0.1; c = vec4(s0, r, seed, 1.0);",
        {
            1: (
                lambda s: np.where(s < 20.0, (s + K) + K2, s + K),
                lambda s: np.where(s < 20.0, _merged(s, 3), s + K),
            ),
            2: (
                lambda s: np.where(s < 20.0, _steps(s, 4), _steps(s, 2)),
                lambda s: np.where(s < 20.0, _merged(s, 3), s + K) + K,
            ),
        },
    ),
    "a_callee_calling_in_a_branch": (
        "seed += 0.1; vec2 h = hash2_if(seed, s0); c = vec4(s0, seed, h);",
        {
            1: (
                lambda s: np.where(s < 20.0, (s + K) + K2, s + K),
                lambda s: np.where(s < 20.0, _merged(s, 3), s + K),
            )
        },
    ),
}
# A call in an arm of the caller's ``if``: the arm is dominated by the chain before the ``if``
# (not by the other arm), so inlined, the call continues it in either arm.
CALLER_ARMS = {
    "a_call_in_each_arm": (
        "hash2(seed); float r;"
        " if (s0 < 20.0) r = hash2(seed).y; else r = hash2(seed).x * 2.0;"
        " c = vec4(s0, r, 0.0, 1.0);",
        {
            1: (
                lambda s: np.where(s < 20.0, _merged(s, 4), (_merged(s, 2) + K) * 2.0),
                lambda s: np.where(s < 20.0, _merged(s, 4), _merged(s, 3) * 2.0),
            )
        },
    ),
    "a_call_in_the_else_arm": (
        "hash2(seed); float r = 0.0; if (s0 < 20.0) r = seed; else r = hash2(seed).y;"
        " c = vec4(s0, r, 0.0, 1.0);",
        {
            1: (
                lambda s: np.where(s < 20.0, _merged(s, 2), _merged(s, 2) + K2),
                lambda s: np.where(s < 20.0, _merged(s, 2), _merged(s, 4)),
            )
        },
    ),
}
# Not followed by the engines: a third copy restarts the chain at the second copy's phi.
BRANCHED_THIRD_COPY = {
    "a_third_copy_after_a_folded_branch": (
        _BRANCHED.format(start="0.0", passes=3),
        {
            1: (
                lambda s: _restarted(s, [K, K], 3),
                lambda s: _restarted(_unrolled(s, [], [K, K], 2, []), [K, K], 1),
            )
        },
    ),
}


# A write in an arm of an ``if`` is an SSA addition of the value before the ``if``: the chain
# runs into either arm (and into a callee writing in arms, once inlined) and stops at the join.
# An unrolled loop whose body writes in arms continues the chain in its first copy only; each
# later copy starts from the phi its arms joined into.
def _arms(then_, else_):
    return lambda s: np.where(s > 20.0, then_(s), else_(s))


def _bounce(first, rest):
    """The seed after `bounce`: its first pass as `first` orders it, then the later passes
    (two, or none where it breaks) each from the pass before."""

    def after(s, then_, else_):
        out = np.where(s > 20.0, first(s, then_), first(s, else_))
        later = np.where(s > 20.0, rest(out, then_), rest(out, else_))
        later = np.where(s > 20.0, rest(later, then_), rest(later, else_))
        return np.where(s > 30.0, out, later)

    return lambda s: after(s, 2, 1)


def _passes(first, rest):
    """The seed after three passes of ``arms``: its first as `first` orders it, the two later
    ones each from the pass before as `rest` does."""

    def after(s, n):
        out = first(s, n)
        for _ in range(2):
            out = rest(out, n)
        return out

    return lambda s: np.where(s > 20.0, after(s, 2), after(s, 1))


def _returning(second, third):
    """The seed after `returning`: merged in its first arm, `second` and `third` (its second
    arm, what follows both) ordered as given."""
    return lambda s: np.where(s > 30.0, _merged(s, 3), np.where(s > 10.0, second(s), third(s)))


IN_ARMS = {
    "into_an_else_arm": (
        "seed += 0.1; seed += 0.1; if (s0 > 20.0) { seed += 0.1; } else { seed += 0.7; }"
        " c = vec4(s0, seed, 0.0, 1.0);",
        {
            1: (
                _arms(lambda s: _steps(s, 3), lambda s: _merged(s, 2) + np.float32(0.7)),
                _arms(lambda s: _merged(s, 3), lambda s: s + ((np.float32(0.7) + K) + K)),
            )
        },
    ),
    "into_a_callee_writing_in_arms": (
        "seed += 0.1; arms(seed, s0); c = vec4(s0, seed, 0.0, 1.0);",
        {
            1: (
                _arms(lambda s: _steps(s, 3), lambda s: _steps(s, 2)),
                _arms(lambda s: _merged(s, 3), lambda s: _merged(s, 2)),
            )
        },
    ),
    "past_an_arm_that_returns": (
        "seed += 0.1; returning(seed, s0); c = vec4(s0, seed, 0.0, 1.0);",
        {
            1: (
                _returning(lambda s: _steps(s, 2), lambda s: _merged(s, 1) + (K + K)),
                _returning(lambda s: _merged(s, 2), lambda s: _merged(s, 3)),
            )
        },
    ),
    "a_global_past_an_arm_that_returns": (
        "gseed = s0; gseed += 0.1; greturning(s0); c = vec4(s0, gseed, 0.0, 1.0);",
        {
            1: (
                _returning(lambda s: _steps(s, 2), lambda s: _merged(s, 1) + (K + K)),
                _returning(lambda s: _merged(s, 2), lambda s: _merged(s, 3)),
            )
        },
    ),
    "into_the_first_pass_of_a_loop_with_arms": (
        "seed += 0.1; bounce(seed, s0); c = vec4(s0, seed, 0.0, 1.0);",
        {
            1: (
                _bounce(
                    lambda s, n: _merged(s, 1) + _merged(np.float32(0.0), n),
                    lambda s, n: _merged(s, n),
                ),
                _bounce(lambda s, n: _merged(s, n + 1), lambda s, n: _merged(s, n)),
            )
        },
    ),
    "into_the_first_pass_of_a_loop_calling_a_callee_writing_in_arms": (
        "seed += 0.1; for (int j = 0; j < 3; j++) { arms(seed, s0); }"
        " c = vec4(s0, seed, 0.0, 1.0);",
        {
            1: (
                _passes(
                    lambda s, n: _merged(s, 1) + _merged(np.float32(0.0), n),
                    lambda s, n: _merged(s, n),
                ),
                _passes(lambda s, n: _merged(s, n + 1), lambda s, n: _merged(s, n)),
            )
        },
    ),
    "into_a_callee_writing_in_an_arm_after_its_unrolled_loop": (
        "seed += 0.1; looped(seed, s0); float r = seed; seed += 0.1; c = vec4(s0, r, seed, 1.0);",
        {
            1: (
                _arms(lambda s: _steps(s, 5), lambda s: _steps(s, 3)),
                _arms(
                    lambda s: _unrolled(s, [K], [K], 2, [K, K]),
                    lambda s: _unrolled(s, [K], [K], 2, []),
                ),
            ),
            2: (
                _arms(
                    lambda s: _unrolled(s, [K], [K], 2, [K, K, K]),
                    lambda s: _unrolled(s, [K], [K], 2, [K]),
                ),
                lambda s: (
                    _arms(
                        lambda s: _unrolled(s, [K], [K], 2, [K, K]),
                        lambda s: _unrolled(s, [K], [K], 2, []),
                    )(s)
                    + K
                ),
            ),
        },
    ),
}


def _restarted(s0, body, times):
    """A loop NIR keeps: the body's constants merged, the chain restarted at each pass."""
    step = np.float32(0.0)
    for k in body:
        step = step + k
    out = s0
    for _ in range(times):
        out = out + step
    return out


def _sines(n):
    """A loop body of two additions and n lines of 3 instructions each: NIR unrolls 16 passes
    of it up to n = 16 (cost (3n + 2) * 16 against 32 * 26)."""
    lines = " ".join(f"a = sin(a * 1.01 + {i}.0);" for i in range(n))
    return (
        f"float a = s0; for (int i = 0; i < 16; i++) {{ seed += 0.1; seed += 0.2; {lines} }}"
        " c = vec4(s0, seed, a, 1.0);"
    )


def _atans(n, passes, two=False):
    """A loop body of two additions and n lines of atan (``atan(y, x)`` with `two`): NIR
    unrolls 4 passes of atan lines up to n = 6, 2 passes of atan(y, x) lines up to n = 7
    (loop_unroll.py: 29 and 50 instructions a component)."""
    y_x = "a * 1.01 + {}.0, a + 0.5" if two else "a * 1.01 + {}.0"
    lines = " ".join(f"a = atan({y_x.format(i + 1)});" for i in range(n))
    return (
        f"float a = s0; for (int i = 0; i < {passes}; i++) {{ seed += 0.1; seed += 0.2; {lines} }}"
        " c = vec4(s0, seed, a, 1.0);"
    )


def _orders(passes, unrolled):
    """The channel of the seed: (the other order, Mesa's) for a loop NIR unrolls or keeps."""
    kept = lambda s: _restarted(s, [K, K2], passes)  # noqa: E731
    copies = lambda s: _unrolled(s, [], [K, K2], passes, [])  # noqa: E731
    return {1: (kept, copies) if unrolled else (copies, kept)}


# An unrolled loop whose body adds two constants merges them first, ``phi + (0.1 + 0.1)``, then
# each copy's sum into the one before; a loop whose body costs too much is kept.
UNROLLED_BODIES = {
    "small_enough_to_unroll": (
        _sines(16),
        {1: (lambda s: _restarted(s, [K, K2], 16), lambda s: _unrolled(s, [], [K, K2], 16, []))},
    ),
    "one_line_too_big_to_unroll": (
        _sines(17),
        {1: (lambda s: _unrolled(s, [], [K, K2], 16, []), lambda s: _restarted(s, [K, K2], 16))},
    ),
    "atan_lines_unrolled": (_atans(6, 4), _orders(4, True)),
    "one_atan_line_too_many_to_unroll": (_atans(7, 4), _orders(4, False)),
    "atan2_lines_unrolled": (_atans(7, 2, two=True), _orders(2, True)),
    "one_atan2_line_too_many_to_unroll": (_atans(8, 2, two=True), _orders(2, False)),
    "unrolled_loop_of_two_steps": (
        "for (int i = 0; i < 4; i++) { seed += 0.1; seed += 0.1; } c = vec4(s0, seed, 0.0, 1.0);",
        {1: (lambda s: _merged(s, 8), lambda s: _unrolled(s, [], [K, K], 4, []))},
    ),
}


def _unrolled(s0, pre, body, times, post):
    """NIR's order for a loop it unrolls, as measured: the body's constants merged first
    (``phi + (c1 + c2)``), the copies' sums added up, then the constants `pre` before the loop
    (merged left to right) and those `post` after it, one at a time."""
    step = np.float32(0.0)
    for k in body:
        step = step + k
    acc = np.float32(0.0)
    for _ in range(times):
        acc = acc + step
    if pre:
        before = np.float32(0.0)
        for k in pre:
            before = before + k
        acc = acc + before
    for k in post:
        acc = acc + k
    return s0 + acc


def _left_to_right(s0, ks):
    acc = np.float32(0.0)
    for k in ks:
        acc = acc + k
    return s0 + acc


def _text(name, body):
    """The shader of a shape: HEAD's functions (BRANCHED_HEAD's too for BRANCHED_CALLEES), then
    `body` in mainImage."""
    head = HEAD
    if name in BRANCHED_CALLEES:
        head = HEAD.replace("void mainImage", BRANCHED_HEAD + "void mainImage")
    return head + body + "\n}"


def _render(shader, backend):
    return render(shader, backend, frame=0).reshape(-1, 4)


MEASURED = {
    **SHAPES,
    **THROUGH_CALLS,
    **UNROLLED_BODIES,
    **BRANCHED_CALLS,
    **BRANCHED_THIRD_COPY,
    **BRANCHED_CALLEES,
    **IN_ARMS,
    **CALLER_ARMS,
}


@pytest.mark.parametrize("name", sorted(MEASURED))
def test_llvmpipe_merges_the_constants_of_a_repeated_sum(llvmpipe, make_shader, name):
    """The driver's value is the merged order on every pixel, and the shape tells the orders
    apart (else the comparison proves nothing)."""
    body, channels = MEASURED[name]
    got = _render(make_shader(_text(name, body)), "gl")
    s0 = got[:, 0]
    for ch, (stepwise, merged) in channels.items():
        want, other = merged(s0).astype(np.float32), stepwise(s0).astype(np.float32)
        assert (want != other).any(), (name, ch)
        assert (got[:, ch].view(np.int32) == want.view(np.int32)).all(), (name, ch)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_numpy_merges_the_constants_of_a_repeated_sum_as_mesa(
    renders_as_llvmpipe, make_shader, name
):
    renders_as_llvmpipe(make_shader(HEAD + SHAPES[name][0] + "\n}"), name=name, frame=0)


FOLLOWED = {
    **THROUGH_CALLS,
    **UNROLLED_BODIES,
    **BRANCHED_CALLS,
    **BRANCHED_CALLEES,
    **CALLER_ARMS,
}


@pytest.mark.parametrize("name", sorted(FOLLOWED))
def test_numpy_merges_the_constants_through_calls_as_mesa(renders_as_llvmpipe, make_shader, name):
    shader = make_shader(_text(name, FOLLOWED[name][0]))
    renders_as_llvmpipe(shader, name=name, frame=0)


@pytest.mark.parametrize("name", sorted(IN_ARMS))
def test_numpy_merges_the_constants_in_arms_as_mesa(renders_as_llvmpipe, make_shader, name):
    renders_as_llvmpipe(make_shader(_text(name, IN_ARMS[name][0])), name=name, frame=0)


@pytest.mark.parametrize("lanes", [0, 8])
@pytest.mark.parametrize("name", sorted(IN_ARMS))
def test_compiled_merges_the_constants_in_arms_as_mesa(llvmpipe, numba, make_shader, name, lanes):
    """The compiled engine per pixel and in lockstep (its `lanes`), against the driver."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(_text(name, IN_ARMS[name][0]))
    want = render(shader, "gl", frame=0)
    got = CompiledProgram(*generate(shader, lanes=lanes)).render(size=SIZE, time=0.0, frame=0)
    assert_same(got, want, what=f"{name}, lanes {lanes}", names=("compiled", "llvmpipe"))


# Every shape of a global passed to an ``inout`` parameter above, and the calls advancing a
# seed in a loop NIR keeps, in one shader whose merged constants each change the output's bits.
GLOBAL_ARGUMENTS = (
    "gseed = s0; vec2 h = hash2(gseed); h += hash2(gseed); float r = gseed; h += two();"
    " h += hash2_reading(gseed); scale(); h += shash(gseed); h += hash2_aliased(gseed);"
    " for (int i = 0; i < 3; i++) { h += hash2(gseed); } gwalk(); h.x += walk(seed);"
    " c = vec4(h, r, gseed);"
)


@pytest.mark.parametrize("lanes", [0, 8])
def test_compiled_merges_the_constants_of_a_global_argument_as_mesa(
    llvmpipe, numba, make_shader, lanes
):
    """The compiled engine per pixel and in lockstep (its `lanes`), against the driver."""
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(HEAD + GLOBAL_ARGUMENTS + "\n}")
    want = render(shader, "gl", frame=0)
    got = CompiledProgram(*generate(shader, lanes=lanes)).render(size=SIZE, time=0.0, frame=0)
    assert_same(got, want, what=f"lanes {lanes}", names=("compiled", "llvmpipe"))


@pytest.mark.parametrize("lanes", [0, 8])
@pytest.mark.parametrize(
    "name", sorted(BRANCHED_CALLS) + sorted(BRANCHED_CALLEES) + sorted(CALLER_ARMS)
)
def test_compiled_follows_a_call_in_a_branch_as_mesa(llvmpipe, numba, make_shader, name, lanes):
    from glslcheck.backends.compiled_engine.engine import CompiledProgram, generate

    shader = make_shader(
        _text(name, {**BRANCHED_CALLS, **BRANCHED_CALLEES, **CALLER_ARMS}[name][0])
    )
    want = render(shader, "gl", frame=0)
    got = CompiledProgram(*generate(shader, lanes=lanes)).render(size=SIZE, time=0.0, frame=0)
    assert_same(got, want, what=f"{name}, lanes {lanes}", names=("compiled", "llvmpipe"))
