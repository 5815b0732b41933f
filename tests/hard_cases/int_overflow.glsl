// Hard case: integer overflow. GLSL ES 3.00 ints are 32-bit two's complement and wrap
// (spec 4.1.3: "operations resulting in overflow or underflow will not cause any exception"),
// as typical integer hashes rely on: a multiply-xor hash, an LCG step, a Knuth multiplicative
// hash in uint, and INT_MAX + 1 = INT_MIN.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    ivec2 p = ivec2(fragCoord);
    int frame = int(floor(iTime * 10.0));
    int h = (p.x * 73856093) ^ (p.y * 19349663) ^ (frame * 83492791);
    h = h * 1103515245 + 12345;
    uint u = uint(h) * 2654435761u;
    int big = 2147483647 + p.x;   // negative from p.x = 1 on
    fragColor = vec4(float(h & 255) / 255.0,
                     float((u >> 24) & 255u) / 255.0,
                     big < 0 ? 0.25 + 0.5 * float(big) / -2147483648.0 : 0.0,
                     1.0);
}
