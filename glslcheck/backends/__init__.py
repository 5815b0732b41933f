"""The backends behind one interface: the NumPy engine and the compiled (numba) engine on the CPU,
OpenGL (moderngl, Mesa's llvmpipe) and WebGL 2 (headless Chromium); registry compiles a shader
for any of them."""
