// Hard case: pow(0, 0), pow(0, y < 0) and pow of a negative base, with run-time operands.
// x is exactly 0 on the middle column and negative left of it; y is exactly 0 on the middle row.
// GLSL leaves pow undefined for x < 0 and for x = 0, y <= 0; llvmpipe computes exp2(y*log2(x)):
// NaN for x < 0 and 0 for x = 0 whatever y is (pow(0, 0) = 0, not 1).
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 centre = floor(iResolution.xy * 0.5) + 0.5;
    float x = (fragCoord.x - centre.x) / 16.0;
    float y = (fragCoord.y - centre.y) / 8.0 + floor(iTime);
    fragColor = vec4(pow(x, y), pow(abs(x), y) * 0.25, pow(abs(x), 0.5 * y), 1.0);
}
