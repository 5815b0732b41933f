"""The `__init__` templates of the lint path, compiled ahead of time (see `init_code` in
glslcheck/base/records.py). Written by `python -m glslcheck.base.records`; do not edit.
"""

# `_set0`, `_set1`, ... and `_Factory` are the globals each class's `__init__` is given
# where it is made (records._make_init, frontend/syntax.py), not names of this module.
# mypy: disable-error-code="name-defined"


def _t0(self):
    pass


def _t1(self, *, loc):
    self.loc = loc


def _t2(self, _f0):
    _set0(self, _f0)


def _t3(self, _f0, *, loc):
    self._f0 = _f0.make() if type(_f0) is _Factory else _f0
    self.loc = loc


def _t4(self, _f0, _f1):
    _set0(self, _f0)
    _set1(self, _f1)


def _t5(self, _f0, _f1, *, loc):
    self._f0 = _f0.make() if type(_f0) is _Factory else _f0
    self._f1 = _f1.make() if type(_f1) is _Factory else _f1
    self.loc = loc


def _t6(self, _f0, _f1, _f2):
    _set0(self, _f0)
    _set1(self, _f1)
    _set2(self, _f2)


def _t7(self, _f0, _f1, _f2):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2


def _t8(self, _f0, _f1, _f2):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2.make() if type(_f2) is _Factory else _f2


def _t9(self, _f0, _f1, _f2):
    self._f0 = _f0.make() if type(_f0) is _Factory else _f0
    self._f1 = _f1
    self._f2 = _f2


def _t10(self, _f0, _f1, _f2, *, loc):
    self._f0 = _f0.make() if type(_f0) is _Factory else _f0
    self._f1 = _f1.make() if type(_f1) is _Factory else _f1
    self._f2 = _f2.make() if type(_f2) is _Factory else _f2
    self.loc = loc


def _t11(self, _f0, _f1, _f2, _f3):
    _set0(self, _f0)
    _set1(self, _f1)
    _set2(self, _f2)
    _set3(self, _f3)


def _t12(self, _f0, _f1, _f2, _f3):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3


def _t13(self, _f0, _f1, _f2, _f3):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2.make() if type(_f2) is _Factory else _f2
    self._f3 = _f3.make() if type(_f3) is _Factory else _f3


def _t14(self, _f0, _f1, _f2, _f3):
    self._f0 = _f0.make() if type(_f0) is _Factory else _f0
    self._f1 = _f1
    self._f2 = _f2.make() if type(_f2) is _Factory else _f2
    self._f3 = _f3


def _t15(self, _f0, _f1, _f2, _f3, *, loc):
    self._f0 = _f0.make() if type(_f0) is _Factory else _f0
    self._f1 = _f1.make() if type(_f1) is _Factory else _f1
    self._f2 = _f2.make() if type(_f2) is _Factory else _f2
    self._f3 = _f3.make() if type(_f3) is _Factory else _f3
    self.loc = loc


def _t16(self, _f0, _f1, _f2, _f3, _f4):
    _set0(self, _f0)
    _set1(self, _f1)
    _set2(self, _f2)
    _set3(self, _f3)
    _set4(self, _f4)


def _t17(self, _f0, _f1, _f2, _f3, _f4):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3
    self._f4 = _f4


def _t18(self, _f0, _f1, _f2, _f3, _f4, *, loc):
    self._f0 = _f0.make() if type(_f0) is _Factory else _f0
    self._f1 = _f1.make() if type(_f1) is _Factory else _f1
    self._f2 = _f2.make() if type(_f2) is _Factory else _f2
    self._f3 = _f3.make() if type(_f3) is _Factory else _f3
    self._f4 = _f4.make() if type(_f4) is _Factory else _f4
    self.loc = loc


def _t19(self, _f0, _f1, _f2, _f3, _f4, _f5):
    _set0(self, _f0)
    _set1(self, _f1)
    _set2(self, _f2)
    _set3(self, _f3)
    _set4(self, _f4)
    _set5(self, _f5)


def _t20(self, _f0, _f1, _f2, _f3, _f4, _f5):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3
    self._f4 = _f4
    self._f5 = _f5.make() if type(_f5) is _Factory else _f5


def _t21(self, _f0, _f1, _f2, _f3, _f4, _f5, *, loc):
    self._f0 = _f0.make() if type(_f0) is _Factory else _f0
    self._f1 = _f1.make() if type(_f1) is _Factory else _f1
    self._f2 = _f2.make() if type(_f2) is _Factory else _f2
    self._f3 = _f3.make() if type(_f3) is _Factory else _f3
    self._f4 = _f4.make() if type(_f4) is _Factory else _f4
    self._f5 = _f5.make() if type(_f5) is _Factory else _f5
    self.loc = loc


def _t22(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6):
    _set0(self, _f0)
    _set1(self, _f1)
    _set2(self, _f2)
    _set3(self, _f3)
    _set4(self, _f4)
    _set5(self, _f5)
    _set6(self, _f6)


def _t23(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3
    self._f4 = _f4
    self._f5 = _f5.make() if type(_f5) is _Factory else _f5
    self._f6 = _f6


def _t24(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7):
    _set0(self, _f0)
    _set1(self, _f1)
    _set2(self, _f2)
    _set3(self, _f3)
    _set4(self, _f4)
    _set5(self, _f5)
    _set6(self, _f6)
    _set7(self, _f7)


def _t25(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3
    self._f4 = _f4
    self._f5 = _f5.make() if type(_f5) is _Factory else _f5
    self._f6 = _f6
    self._f7 = _f7


def _t26(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3
    self._f4 = _f4
    self._f5 = _f5
    self._f6 = _f6.make() if type(_f6) is _Factory else _f6
    self._f7 = _f7.make() if type(_f7) is _Factory else _f7
    self._f8 = _f8.make() if type(_f8) is _Factory else _f8


def _t27(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3
    self._f4 = _f4
    self._f5 = _f5.make() if type(_f5) is _Factory else _f5
    self._f6 = _f6
    self._f7 = _f7
    self._f8 = _f8


def _t28(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8, _f9):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3
    self._f4 = _f4
    self._f5 = _f5
    self._f6 = _f6
    self._f7 = _f7
    self._f8 = _f8.make() if type(_f8) is _Factory else _f8
    self._f9 = _f9


def _t29(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8, _f9, _f10):
    _set0(self, _f0)
    _set1(self, _f1)
    _set2(self, _f2)
    _set3(self, _f3)
    _set4(self, _f4)
    _set5(self, _f5)
    _set6(self, _f6)
    _set7(self, _f7)
    _set8(self, _f8)
    _set9(self, _f9)
    _set10(self, _f10)


def _t30(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8, _f9, _f10, _f11, _f12, _f13):
    self._f0 = _f0
    self._f1 = _f1
    self._f2 = _f2
    self._f3 = _f3
    self._f4 = _f4
    self._f5 = _f5
    self._f6 = _f6
    self._f7 = _f7
    self._f8 = _f8
    self._f9 = _f9.make() if type(_f9) is _Factory else _f9
    self._f10 = _f10
    self._f11 = _f11
    self._f12 = _f12.make() if type(_f12) is _Factory else _f12
    self._f13 = _f13.make() if type(_f13) is _Factory else _f13


SOURCES = {
    'def __init__(self):\n    pass': _t0,
    'def __init__(self, *, loc):\n    self.loc = loc': _t1,
    'def __init__(self, _f0):\n    _set0(self, _f0)': _t2,
    'def __init__(self, _f0, *, loc):\n    self._f0 = _f0.make() if type(_f0) is _Factory else _f0\n    self.loc = loc': _t3,
    'def __init__(self, _f0, _f1):\n    _set0(self, _f0)\n    _set1(self, _f1)': _t4,
    'def __init__(self, _f0, _f1, *, loc):\n    self._f0 = _f0.make() if type(_f0) is _Factory else _f0\n    self._f1 = _f1.make() if type(_f1) is _Factory else _f1\n    self.loc = loc': _t5,
    'def __init__(self, _f0, _f1, _f2):\n    _set0(self, _f0)\n    _set1(self, _f1)\n    _set2(self, _f2)': _t6,
    'def __init__(self, _f0, _f1, _f2):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2': _t7,
    'def __init__(self, _f0, _f1, _f2):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2.make() if type(_f2) is _Factory else _f2': _t8,
    'def __init__(self, _f0, _f1, _f2):\n    self._f0 = _f0.make() if type(_f0) is _Factory else _f0\n    self._f1 = _f1\n    self._f2 = _f2': _t9,
    'def __init__(self, _f0, _f1, _f2, *, loc):\n    self._f0 = _f0.make() if type(_f0) is _Factory else _f0\n    self._f1 = _f1.make() if type(_f1) is _Factory else _f1\n    self._f2 = _f2.make() if type(_f2) is _Factory else _f2\n    self.loc = loc': _t10,
    'def __init__(self, _f0, _f1, _f2, _f3):\n    _set0(self, _f0)\n    _set1(self, _f1)\n    _set2(self, _f2)\n    _set3(self, _f3)': _t11,
    'def __init__(self, _f0, _f1, _f2, _f3):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3': _t12,
    'def __init__(self, _f0, _f1, _f2, _f3):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2.make() if type(_f2) is _Factory else _f2\n    self._f3 = _f3.make() if type(_f3) is _Factory else _f3': _t13,
    'def __init__(self, _f0, _f1, _f2, _f3):\n    self._f0 = _f0.make() if type(_f0) is _Factory else _f0\n    self._f1 = _f1\n    self._f2 = _f2.make() if type(_f2) is _Factory else _f2\n    self._f3 = _f3': _t14,
    'def __init__(self, _f0, _f1, _f2, _f3, *, loc):\n    self._f0 = _f0.make() if type(_f0) is _Factory else _f0\n    self._f1 = _f1.make() if type(_f1) is _Factory else _f1\n    self._f2 = _f2.make() if type(_f2) is _Factory else _f2\n    self._f3 = _f3.make() if type(_f3) is _Factory else _f3\n    self.loc = loc': _t15,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4):\n    _set0(self, _f0)\n    _set1(self, _f1)\n    _set2(self, _f2)\n    _set3(self, _f3)\n    _set4(self, _f4)': _t16,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3\n    self._f4 = _f4': _t17,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, *, loc):\n    self._f0 = _f0.make() if type(_f0) is _Factory else _f0\n    self._f1 = _f1.make() if type(_f1) is _Factory else _f1\n    self._f2 = _f2.make() if type(_f2) is _Factory else _f2\n    self._f3 = _f3.make() if type(_f3) is _Factory else _f3\n    self._f4 = _f4.make() if type(_f4) is _Factory else _f4\n    self.loc = loc': _t18,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5):\n    _set0(self, _f0)\n    _set1(self, _f1)\n    _set2(self, _f2)\n    _set3(self, _f3)\n    _set4(self, _f4)\n    _set5(self, _f5)': _t19,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3\n    self._f4 = _f4\n    self._f5 = _f5.make() if type(_f5) is _Factory else _f5': _t20,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, *, loc):\n    self._f0 = _f0.make() if type(_f0) is _Factory else _f0\n    self._f1 = _f1.make() if type(_f1) is _Factory else _f1\n    self._f2 = _f2.make() if type(_f2) is _Factory else _f2\n    self._f3 = _f3.make() if type(_f3) is _Factory else _f3\n    self._f4 = _f4.make() if type(_f4) is _Factory else _f4\n    self._f5 = _f5.make() if type(_f5) is _Factory else _f5\n    self.loc = loc': _t21,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6):\n    _set0(self, _f0)\n    _set1(self, _f1)\n    _set2(self, _f2)\n    _set3(self, _f3)\n    _set4(self, _f4)\n    _set5(self, _f5)\n    _set6(self, _f6)': _t22,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3\n    self._f4 = _f4\n    self._f5 = _f5.make() if type(_f5) is _Factory else _f5\n    self._f6 = _f6': _t23,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7):\n    _set0(self, _f0)\n    _set1(self, _f1)\n    _set2(self, _f2)\n    _set3(self, _f3)\n    _set4(self, _f4)\n    _set5(self, _f5)\n    _set6(self, _f6)\n    _set7(self, _f7)': _t24,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3\n    self._f4 = _f4\n    self._f5 = _f5.make() if type(_f5) is _Factory else _f5\n    self._f6 = _f6\n    self._f7 = _f7': _t25,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3\n    self._f4 = _f4\n    self._f5 = _f5\n    self._f6 = _f6.make() if type(_f6) is _Factory else _f6\n    self._f7 = _f7.make() if type(_f7) is _Factory else _f7\n    self._f8 = _f8.make() if type(_f8) is _Factory else _f8': _t26,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3\n    self._f4 = _f4\n    self._f5 = _f5.make() if type(_f5) is _Factory else _f5\n    self._f6 = _f6\n    self._f7 = _f7\n    self._f8 = _f8': _t27,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8, _f9):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3\n    self._f4 = _f4\n    self._f5 = _f5\n    self._f6 = _f6\n    self._f7 = _f7\n    self._f8 = _f8.make() if type(_f8) is _Factory else _f8\n    self._f9 = _f9': _t28,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8, _f9, _f10):\n    _set0(self, _f0)\n    _set1(self, _f1)\n    _set2(self, _f2)\n    _set3(self, _f3)\n    _set4(self, _f4)\n    _set5(self, _f5)\n    _set6(self, _f6)\n    _set7(self, _f7)\n    _set8(self, _f8)\n    _set9(self, _f9)\n    _set10(self, _f10)': _t29,
    'def __init__(self, _f0, _f1, _f2, _f3, _f4, _f5, _f6, _f7, _f8, _f9, _f10, _f11, _f12, _f13):\n    self._f0 = _f0\n    self._f1 = _f1\n    self._f2 = _f2\n    self._f3 = _f3\n    self._f4 = _f4\n    self._f5 = _f5\n    self._f6 = _f6\n    self._f7 = _f7\n    self._f8 = _f8\n    self._f9 = _f9.make() if type(_f9) is _Factory else _f9\n    self._f10 = _f10\n    self._f11 = _f11\n    self._f12 = _f12.make() if type(_f12) is _Factory else _f12\n    self._f13 = _f13.make() if type(_f13) is _Factory else _f13': _t30,
}
