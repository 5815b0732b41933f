// Hard case: division by zero. Floats follow IEEE (spec 4.5.1 "no exceptions"): 1/0 = +Inf,
// -1/0 = -Inf, 0/0 = NaN. Integer division by zero is undefined; llvmpipe gives 0 for int / 0,
// -1 for int % 0 and 0xFFFFFFFF for uint / 0u. The middle column and row are the zero divisors.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 centre = floor(iResolution.xy * 0.5) + 0.5;
    vec2 d = fragCoord - centre;                  // exactly 0 on the middle column / row
    float f = (d.y + floor(iTime)) / d.x;         // +-Inf on the middle column, NaN at the centre
    ivec2 i = ivec2(d);
    int q = (i.x + 100) / i.y;                    // int / 0 on the middle row
    int r = (i.x + 100) % i.y;                    // int % 0 on the middle row
    uint u = uint(abs(i.x) + 1) * 1000u / uint(abs(i.y));
    fragColor = vec4(f * 0.02 + 0.5,
                     float(q & 63) / 63.0 + float(r == -1) * 0.25,
                     float(u >> 26) / 63.0,
                     1.0);
}
