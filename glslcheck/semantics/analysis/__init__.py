"""Analysis of a checked program that later stages share: dataflow and values.

    from glslcheck.semantics.analysis import program_facts
    facts = program_facts(model)               # ProgramFacts, built once per Model
    for fn in facts.in_file(path):             # FunctionFacts of each function defined there
        fn.key(e), fn.dominates(a, b), fn.reaching_value(ident, sym), fn.value_range(e)

* `dataflow.py`: the execution-order walk of each function (positions, regions, writes, calls),
  value keys (the same value written differently gets one key), purity and cost, dominance,
  writes between two places, reaching values; `written_variable` (which variable an l-value
  writes) and `param_directions` (in/out/inout of a call's arguments), the one answer to each
  for every stage.
* `values.py`: the sign analysis (`value_range`: bounds and why a value can be negative).
* `undefined.py`: where the program reads a value GLSL leaves undefined (`undefined_reads`:
  out parameters, locals and globals read before written (`global_reads` follows the calls),
  integer division by zero, out-of-range shifts and conversions, built-ins outside their
  domain), for `check`, lint, verify and probe.

It reads the semantic model (`glslcheck.semantics.Model`) and the AST only; its users are the lint
rules (glslcheck/lint/rules) and both CPU engines (backends/cpu_core/facts.py and
uniformity.py ask `written_variable` and `param_directions`).
"""

from __future__ import annotations

from .dataflow import (
    FunctionFacts,
    ProgramFacts,
    Write,
    builtin_call,
    builtin_calls,
    calls_in,
    is_float_type,
    program_facts,
)
from .purity import (
    function_cost,
    ignored_parameters,
    param_directions,
    pure_function,
    written_variable,
)
from .undefined import (
    STOPS,
    VARIABLE_KINDS,
    UndefinedRead,
    global_reads,
    origins,
    reached_through,
    stop_notes,
    unassigned_reads,
    undefined_reads,
)
from .values import NONNEGATIVE_UNIFORMS, ValueRanges, numbers

__all__ = [
    "FunctionFacts",
    "ProgramFacts",
    "Write",
    "ValueRanges",
    "UndefinedRead",
    "VARIABLE_KINDS",
    "STOPS",
    "stop_notes",
    "NONNEGATIVE_UNIFORMS",
    "builtin_call",
    "builtin_calls",
    "calls_in",
    "function_cost",
    "ignored_parameters",
    "is_float_type",
    "numbers",
    "param_directions",
    "program_facts",
    "pure_function",
    "written_variable",
    "origins",
    "global_reads",
    "reached_through",
    "unassigned_reads",
    "undefined_reads",
]
