"""lanes_slim's rewrites of a generated function against the function as written: run as plain
Python on the same inputs, the rewritten text returns what the original returns, with fewer
statements where a rewrite applies and the original's statements where one must not.
numba_lowering's remembered type sizes against numba's own."""

from __future__ import annotations

import ast
import random
import textwrap

import numpy as np
import pytest

from glslcheck.backends.compiled_engine import numba_swaps
from glslcheck.backends.compiled_engine.lanes_slim import hoistable_globals, slim_function

MODULE = textwrap.dedent(
    """
    import numpy as np
    F32 = np.float32
    F_7p0 = np.float32(7.0)
    F_1p0 = np.float32(1.0)
    I_2 = np.int32(2)
    FMA = True
    """
)


def lsel(c, a, b):
    return a if c else b


def _run(fn_text: str, args: tuple) -> object:
    env = {"lsel": lsel, "np": np}
    exec(compile(MODULE, "<module>", "exec"), env)
    exec(compile(fn_text, "<fn>", "exec"), env)
    return env["f"](*args)


def _slim(fn_text: str) -> str:
    constants, own = hoistable_globals(ast.parse(MODULE + "\ndef f():\n    pass\n"))
    return slim_function(textwrap.dedent(fn_text), constants, own)


def _statements(text: str) -> int:
    return sum(isinstance(n, ast.stmt) for n in ast.walk(ast.parse(text))) - 1  # (the def)


def _same(fn_text: str, args_list: list) -> str:
    slim = _slim(fn_text)
    for args in args_list:
        assert _run(slim, args) == _run(textwrap.dedent(fn_text), args), (slim, args)
    return slim


def _floats(n: int) -> list:
    rnd = random.Random(5)
    return [
        tuple(np.float32(rnd.choice([0.0, 3.0, 7.0, 8.0, 14.0, -2.5])) for _ in range(3))
        for _ in range(n)
    ]


TABLE = """
def f(x__0, x__1, y):
    v__0 = F_1p0
    v__1 = F_1p0
    _t1 = y == F_7p0
    _t2__0 = x__0 <= F_7p0
    _t2__1 = x__1 <= F_7p0
    _t3__0 = lsel(_t2__0, F_7p0, F_1p0)
    _t3__1 = lsel(_t2__1, F_7p0, F_1p0)
    _t4__0 = lsel(_t1, _t3__0, v__0)
    _t4__1 = lsel(_t1, _t3__1, v__1)
    v__0 = _t4__0
    v__1 = _t4__1
    _t5 = y == F_1p0
    _t6__0 = x__0 <= F_7p0
    _t6__1 = x__1 <= F_7p0
    _t7__0 = lsel(_t6__0, F_1p0, F_7p0)
    _t7__1 = lsel(_t6__1, F_1p0, F_7p0)
    _t8__0 = lsel(_t5, _t7__0, v__0)
    _t8__1 = lsel(_t5, _t7__1, v__1)
    v__0 = _t8__0
    v__1 = _t8__1
    return (v__0, v__1)
"""


def test_a_table_of_selects_computes_the_same_with_fewer_statements():
    slim = _same(TABLE, _floats(40))
    body = slim.split("\n", 1)[1]
    assert "_t6__" not in body  # the repeated compare: the first one's value
    assert "= _t4__" not in body and "= _t8__" not in body  # copies into v folded
    assert "_g_F_7p0 = F_7p0" in slim and "lsel(" not in body.replace("_g_lsel(", "")
    assert _statements(slim) < _statements(textwrap.dedent(TABLE))


def test_a_value_is_not_shared_across_a_write_of_its_names():
    text = """
    def f(x, y, z):
        _t1 = x <= F_7p0
        x = y
        _t2 = x <= F_7p0
        return (_t1, _t2, z)
    """
    slim = _same(text, _floats(40))
    assert "_t2 = " in slim


def test_a_value_written_before_a_loop_and_in_it_is_kept():
    # the loop's first pass reads the _t2 of before the loop, where _t1 is not computed yet
    text = """
    def f(x, y, z):
        n = 0
        acc = F_1p0
        _t2 = x <= F_7p0
        while True:
            acc = lsel(_t2, acc + F_1p0, acc)
            x = x + y
            _t1 = x <= F_7p0
            _t2 = x <= F_7p0
            n = n + 1
            if n > 4:
                break
        return (acc, _t1, z)
    """
    slim = _same(text, _floats(40))
    assert "_t2 = x" in slim.split("while True:")[1]


def test_values_are_shared_exactly_when_their_trees_are_the_same():
    # a select inside arithmetic is shared; constants Python takes for equal but of other types
    # (0 and 0.0, 1 and 1.0) and an operator outside the pure set (**) are not
    text = """
    def f(x, y, z):
        _t1 = x * F_1p0 + lsel(y == F_7p0, F_1p0, z)
        _t2 = x * F_1p0 + lsel(y == F_7p0, F_1p0, z)
        _t3 = x + 0.0
        _t4 = x + 0
        _t5 = x * 1
        _t6 = x * 1.0
        _t7 = x ** 2
        _t8 = x ** 2
        return (_t1 + _t2, _t3, _t4, _t5 + _t6, _t7 + _t8, z)
    """
    slim = _same(text, _floats(40))
    kept = {
        s.targets[0].id
        for s in ast.parse(slim).body[0].body  # type: ignore[attr-defined]
        if isinstance(s, ast.Assign) and isinstance(s.targets[0], ast.Name)
    }
    assert "_t2" not in kept
    assert {"_t1", "_t3", "_t4", "_t5", "_t6", "_t7", "_t8"} <= kept


def test_a_copy_is_kept_when_its_name_is_read_between():
    text = """
    def f(x, y, z):
        v = y
        _t1 = x + F_1p0
        w = v * F_7p0
        v = _t1
        return (v, w, z)
    """
    slim = _same(text, _floats(20))
    assert "v = _t1" in slim


def test_settings_and_static_indices_stay_globals():
    text = """
    def f(x, y, a):
        if FMA:
            x = x + F_1p0
        if FMA:
            x = x * F_1p0
        return (a[I_2], a[I_2], x)
    """
    args = [(np.float32(2.0), np.float32(1.0), np.arange(4, dtype=np.float32))]
    slim = _same(text, args)
    assert "_g_FMA" not in slim and "_g_I_2" not in slim and "_g_F_1p0" in slim


def test_type_sizes_as_numba_gives_them(numba):
    from llvmlite import ir
    from numba.core import base, registry

    from glslcheck.backends.compiled_engine import numba_lowering, numba_patches

    if not numba_patches.install(numba_lowering):
        pytest.skip(f"numba_lowering is not installed on numba other than {numba_lowering.CHECKED}")
    ctx = registry.cpu_target.target_context
    own = numba_swaps.original(base.BaseContext, "get_abi_sizeof")
    i8p = ir.IntType(8).as_pointer()
    kinds = [
        ir.FloatType(),
        ir.DoubleType(),
        ir.IntType(1),
        ir.IntType(8),
        ir.IntType(32),
        ir.IntType(64),
        i8p,
        ir.ArrayType(ir.FloatType(), 3),
        ir.LiteralStructType([i8p, ir.IntType(64), ir.ArrayType(ir.IntType(64), 2)]),
        ir.LiteralStructType([ir.IntType(1), ir.DoubleType(), ir.IntType(8)]),
        ir.VectorType(ir.FloatType(), 8),
    ]
    for t in kinds:
        for _ in range(2):  # the first use, then the remembered one
            assert ctx.get_abi_sizeof(t) == own(ctx, t), t
