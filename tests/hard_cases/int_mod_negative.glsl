// Hard case: int % with negative operands (undefined in GLSL ES 3.00, spec 5.9). llvmpipe at run
// time computes the UNSIGNED remainder of the two's-complement bits: -7 % 2 = 1, 7 % -2 = 7,
// -7 % -3 = -7 (a constant-folded % gives C's -1 instead). Python's % follows the divisor's sign.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    ivec2 c = ivec2(floor(iResolution.xy * 0.5));
    ivec2 d = ivec2(fragCoord) - c;           // negative left of and below the centre
    int m = 7 + int(iTime);
    int r1 = d.x % m;                         // negative dividend
    int r2 = m % (d.y == 0 ? 1 : d.y);        // negative divisor below the centre
    int r3 = d.x % (d.y == 0 ? -3 : d.y);     // both negative in the lower left
    fragColor = vec4(float(r1 & 15) / 15.0, float(r2 & 15) / 15.0, float(r3 & 255) / 255.0, 1.0);
}
