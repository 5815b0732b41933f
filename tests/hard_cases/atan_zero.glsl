// Hard case: atan(0, 0) and atan's signs. GLSL leaves atan(y, x) undefined for x = y = 0;
// llvmpipe's polynomial gives 3*pi/4 at run time (0 when constant-folded). The middle pixel has
// y = x = 0 exactly, the middle row y = 0 (x < 0 gives pi), the middle column x = 0 (pi/2, and
// the one-argument atan(y/x) sees +-Inf there).
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 centre = floor(iResolution.xy * 0.5) + 0.5;
    vec2 d = fragCoord - centre + vec2(0.0, floor(iTime));
    float a = atan(d.y, d.x);                 // [-pi, pi]
    float b = atan(d.y / (d.x == 0.0 && d.y == 0.0 ? 1.0 : d.x));  // +-pi/2 on the column; 0/0 avoided (atan_nan.glsl)
    float c = atan(-d.y, -d.x);               // -0 operands on the axes
    fragColor = vec4((a + 3.14159265) / 6.2831853, b / 3.14159265 + 0.5, (c + 3.14159265) / 6.2831853, 1.0);
}
