"""The GLSL ES 3.00 preprocessor (spec section 3.4), with a map back to the user's files.

This package owns everything between the text of the Shadertoy tabs and the lexer:

- line continuations (backslash-newline) and comments, which are collected as `Comment`s;
- the directives `#define #undef #if #ifdef #ifndef #elif #else #endif #error #pragma
  #extension #version #line` and the null directive `#`;
- macro expansion as in C (argument pre-expansion, rescanning, a macro is never expanded
  inside its own expansion) without the `#` and `##` operators, which GLSL ES does not have;
- `PPResult.locate` / `locate_span`, which map an offset of the expanded text back to the
  user's file, line and column.

Several units (Shadertoy: the Common tab, then the pass's tab) are preprocessed in order as
one program: macros defined in an earlier unit are visible in later ones, while each unit
keeps its own line numbers, and a conditional opened in a unit must be closed in it (the
Common tab is also compiled on its own). Predefined macros: `GL_ES` 1, `__VERSION__` 300,
`GL_FRAGMENT_PRECISION_HIGH` 1, `__LINE__`, `__FILE__`, and in Shadertoy mode
`HW_PERFORMANCE` 1.

The expanded text keeps the user's layout: text without macros is copied as it is (so its
columns match the file), a comment becomes one space or, when it spans lines, as many
newlines; directive lines and lines in inactive `#if` groups become empty lines; each
expansion is written as its tokens separated by single spaces; when a logical line was
joined by backslash-newline (or a macro call spans lines), the missing newlines are added at
its end, so every line of the output starts at the user's line of the same number.
Offsets inside an expansion map to the whole outermost macro use (name to closing paren).

`#line N [M]` only changes what `__LINE__` and `__FILE__` expand to; locations keep pointing
at the real line of the user's file. `__LINE__` counts lines of the unit it is used in.

Runaway macros cannot hang or overflow the stack: more than MAX_EXPANSION_DEPTH nested
expansions, or more than MAX_EXPANSION_TOKENS tokens produced by expansion, is an error.

Errors raise `GlslError` with one `Diagnostic(rule="preprocessor")` located in the user's
file; warnings (a macro name with `__`) are collected in `PPResult.diagnostics`.

The modules, each importing only those before it: `tokens` (pp-tokens), `units` (a unit after
line splicing and comments, with its map back to the file), `result` (`PPResult`, `Macro`),
`context` (the state while reading), `expansion` (macros), `conditions` (`#if` expressions),
`directives`, and `driver` (`preprocess`: units, lines, Shadertoy's `mainImage` call).
"""

from .context import MAX_EXPANSION_DEPTH, MAX_EXPANSION_TOKENS
from .driver import WRAPPER_COLOR, preprocess
from .result import Macro, PPResult
from .units import Comment

__all__ = [
    "preprocess",
    "PPResult",
    "Comment",
    "Macro",
    "MAX_EXPANSION_DEPTH",
    "MAX_EXPANSION_TOKENS",
    "WRAPPER_COLOR",
]
