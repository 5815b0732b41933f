// Hard case: pow of a negative run-time base with a literal exponent.
// GLSL: undefined for x < 0. llvmpipe: Mesa's optimiser rewrites pow(x, 1.0) to x, pow(x, 2.0)
// to x*x and pow(x, 4.0) to (x*x)*(x*x) before run time, so those give 4, 16 ... for x = -2
// while pow(x, 3.0) (and any other exponent) stays exp2(3*log2(x)) = NaN.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float x = -fragCoord.x / iResolution.x;  // in (-1, 0)
    // Blue: pow(x, 4.0) in the top half, pow(x, 3.0) (NaN) in the bottom half.
    float blue = fragCoord.y > 0.5 * iResolution.y ? pow(x, 4.0) * 4.0 : pow(x, 3.0);
    fragColor = vec4(pow(x, 2.0), -pow(x, 1.0), blue, 1.0);
}
