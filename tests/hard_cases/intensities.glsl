// Hard case: tiny and huge intensities (1e-30, 1e30) and overflow to infinity.
// k in (0, 1) per column. Red: log2 of 1e-30*k, a finite tiny value (no subnormals: llvmpipe
// flushes those to zero and NumPy does not). Green: Reinhard tone mapping x/(1+x) of x = 1e30*k
// times up to +-1e9: finite (~1) near the middle row, +-Inf away from it, where Inf/Inf = NaN.
// Blue: exp of a large argument (+Inf at the top, white) plus 1e-30*1e-30 = 0 (below the
// subnormal range, 0 everywhere).
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float k = fragCoord.x / iResolution.x;
    float row = fragCoord.y / iResolution.y;
    float tiny = 1.0e-30 * k;
    float huge = 1.0e30 * k;
    // A run-time gain: Mesa reassociates constant factors (1e30 * 1e9 would fold to +Inf, see
    // reassociation.glsl), so the overflow must not depend on the order of constants.
    float gain = iResolution.x * iResolution.y * (1.0e5 + fract(iTime));
    float x = huge * (row - 0.5) * gain;
    float red = log2(tiny) / -128.0;
    float green = x / (1.0 + x);
    float blue = exp(200.0 * (row - 0.5)) * 1.0e-3 + tiny * tiny * 1.0e30;
    fragColor = vec4(red, green, blue, 1.0);
}
