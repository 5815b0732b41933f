"""The GLSL ES 3.00 language as data: its types (glsl_types) and built-in functions
(builtin_functions), with Shadertoy's uniforms; the lexer, the checker and the backends read
them."""
