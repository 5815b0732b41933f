"""llvmpipe's math, defined once for both CPU engines.

Mesa's llvmpipe lowers sin, cos, tan, exp2, log2 and pow with gallivm's polynomials
(lp_bld_arit.c), and atan, atan(y, x), asin and acos with NIR's own float32 lowerings. This
package holds what both the NumPy engine and the compiled engine compute them from:

- :mod:`.coefficients`: the constants of those algorithms (NumPy only, no numba);
- :mod:`.cube_faces`: which face a cube map's filter reads past an edge (NumPy only, no numba);
- :mod:`.lane`: the one-lane numba functions (bit helpers, the fused multiply-add, the range
  reduction and polynomials) that backends/numpy_engine/jit_kernels.py runs over arrays and
  backends/compiled_engine/scalar.py and lanes_math.py call per pixel. Importing it imports
  numba: the caller points numba's cache first (cpu_core/numba_cache.use_cache_dir).
"""
