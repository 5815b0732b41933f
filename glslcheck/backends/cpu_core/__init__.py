"""The decisions both CPU engines need, computed once from the checked program and shared by
the NumPy transpiler (backends/numpy_engine) and the numba code generator
(backends/compiled_engine), below both: the static facts of a program (facts.py), which
values of a function are the same in every lane (uniformity.py), and what their code writers
share (common.py). Nothing here writes code of either engine."""
