"""The memo of the Mesa rewrites both CPU engines share (nir_fold, call_fold.py, inline.py,
constant_flow.py): what they computed once about the program being translated, owned by the
engine that asks them (the NumPy Transpiler's `fold_state`, or nir_fold's FoldContext; one per
program) and keyed by the ids of syntax nodes and symbols of that program."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass
class FoldState:
    """Per-transpile caches of the rewrites; each field names the question it memoizes."""

    # nir_fold: per function (id of its symbol) or per node
    mix: dict = field(default_factory=dict)  # function -> mix components sharing t and x (or y)
    lowp: dict = field(default_factory=dict)  # node -> kind of a lowp lookup tree
    lowp_written: set | None = None  # ids of the float16 tree being emitted in its written form
    kept: dict = field(default_factory=dict)  # product kept whole -> (its type, the lines list)
    writes: dict = field(default_factory=dict)  # value node -> the write that stored it
    merge_reads: dict = field(default_factory=dict)  # function -> reads of merged locals
    reads: dict = field(default_factory=dict)  # function body -> symbol -> number of reads
    parents: dict = field(default_factory=dict)  # root -> node -> use counts
    facts: dict = field(default_factory=dict)  # function -> analysis.dataflow FunctionFacts
    written: dict = field(default_factory=dict)  # function -> ids of the symbols it writes
    components: dict = field(default_factory=dict)  # component write -> its record
    component_locals: dict = field(default_factory=dict)  # function -> locals written per component
    component_reads: dict = field(default_factory=dict)  # function -> component reads
    constant_components: dict = field(default_factory=dict)  # node -> a constructor in reach
    component_inits: dict = field(default_factory=dict)  # function -> initializer -> declarator
    undo: dict = field(default_factory=dict)  # `+= e` -> the later `-= e` that cancels it
    kept_products: dict = field(default_factory=dict)  # `x *= b` -> (lines, its operands)
    sink_reads: dict = field(default_factory=dict)  # function -> reads a sunk constant goes through
    fn_facts: dict = field(default_factory=dict)  # function -> FunctionFacts (register_call)
    sunk_returns: dict = field(default_factory=dict)  # function -> its returned `+=` chain
    sink_calls: set | None = None  # functions some call of which has a constant added to its result
    call_k: dict = field(default_factory=dict)  # call -> the constant sunk into its result
    terms: dict = field(default_factory=dict)  # returned term -> its kept code
    # nir_fold/inlined_results.py: function -> a value of its arguments; -> what it returns;
    # call -> an opaque value; node -> its calls all opaque values
    pure_functions: dict = field(default_factory=dict)
    returned_values: dict = field(default_factory=dict)
    opaque_call: dict = field(default_factory=dict)
    opaque_calls: dict = field(default_factory=dict)
    # repeated_sums: (function, chain, symbol) -> (its base, lines); function -> its plan, its
    # chain parameters, their steps; (loop, symbol) -> copies continue it, ("branch", loop,
    # symbol) -> the if its first copy folds (repeated_sums.folded_branch); loop -> pass count
    sum_chains: dict = field(default_factory=dict)
    sum_plans: dict = field(default_factory=dict)
    sum_params: dict = field(default_factory=dict)
    sum_param_steps: dict = field(default_factory=dict)
    sum_loops: dict = field(default_factory=dict)
    sum_index: dict = field(default_factory=dict)
    sum_global_keys: dict = field(default_factory=dict)  # global -> (its chain key, itself)
    # function -> its first-copy loops (id -> loop); function -> the plan of their later passes
    sum_first: dict = field(default_factory=dict)
    sum_later_plans: dict = field(default_factory=dict)
    sum_later: bool = False  # planning those later passes

    loop_costs: dict = field(default_factory=dict)  # loop -> its body's cost (loop_unroll)
    copy_loops: dict = field(default_factory=dict)  # loop -> whether loop_copies counts passes
    copy_values: dict = field(default_factory=dict)  # function -> values merged in loop copies
    kept_slots: dict = field(default_factory=dict)  # value -> (its y's temporary, lines)
    slot_ops: dict = field(default_factory=dict)  # value -> the op a later copy merges with
    sum_globals: list | None = None  # the globals the shader's functions read or write
    sum_global_writers: dict = field(default_factory=dict)  # (function, global) -> writes it
    ray_fns: dict = field(default_factory=dict)  # function -> its ray_dots.RayFn (or None)
    # cpu_core/constant_flow.py
    constant_flow: Any = None  # the program's ConstantFlow, made on first use
    # cpu_core/call_fold.py
    call_fold_off: bool = False  # emitting the written call inside a folded one
    call_fold_dots: dict = field(default_factory=dict)  # function -> whether its body calls dot
    call_fold_globals: dict | None = None  # entry's top-level call -> globals known there
    call_fold_sums: dict = field(
        default_factory=dict
    )  # (call, symbol) -> products summed per component
    call_fold_roots: dict = field(
        default_factory=dict
    )  # (call, symbol) -> root operations per component
    # cpu_core/inline.py
    inline_frames: list = field(default_factory=list)  # the calls being inlined, innermost last
    inline_bodies: dict = field(default_factory=dict)  # function -> its inlinable body
