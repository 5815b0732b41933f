"""The decisions both CPU engines need, computed once from the checked program and shared by
the NumPy transpiler (backends/numpy_engine) and the numba code generator
(backends/compiled_engine), below both: the static facts of a program (facts.py), which
values of a function are the same in every lane (uniformity.py), Mesa's rewrites as llvmpipe
computes them (nir_fold/, with call_fold.py, inline.py and constant_flow.py; their memo
fold_state.py, and fold_protocols.py, what they read of the engine that asks them), what the
code writers share (common.py), and where numba keeps its machine code (numba_cache.py).
Nothing here imports either engine, and nothing here writes code of either engine: a rule
decides what to compute, in which order, with which constants, and builds it from the
operations the engine that asks offers (fold_protocols.FoldEmitter); what an engine writes of
its own is in its package (the NumPy transpiler's: numpy_engine/transpile/binary_rules.py,
call_fold.py, float16.py, returned_sums.py, sum_chains.py). Decisions that are not built from
those operations are data the engine spells: the order a returned sum adds its terms in
(nir_fold.returned_sums.SunkOrder), the name of a `mix` formula (nir_fold.flrp.mix_form); the
few spellings both engines' generated Python shares alike are common.py's."""
