"""The decisions both CPU engines need, computed once from the checked program and shared by
the NumPy transpiler (backends/numpy_engine) and the numba code generator
(backends/compiled_engine), below both: the static facts of a program (facts.py), which
values of a function are the same in every lane (uniformity.py), Mesa's rewrites as llvmpipe
computes them (nir_fold/, with call_fold.py, inline.py and constant_flow.py; their memo
fold_state.py, and fold_protocols.py, what they read of the engine that asks them), what the
code writers share (common.py), and where numba keeps its machine code (numba_cache.py).
Nothing here imports either engine."""
