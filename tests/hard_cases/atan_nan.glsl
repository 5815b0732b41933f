// Hard case: atan of NaN (here atan(0.0 / 0.0) at the middle pixel). IEEE gives NaN; GLSL does
// not require NaN propagation; llvmpipe's polynomial returns 0 (its range reduction compares
// with NaN, and the comparisons are false).
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 centre = floor(iResolution.xy * 0.5) + 0.5;
    vec2 d = fragCoord - centre;
    float b = atan(d.y / d.x);                // NaN argument at the centre, +-Inf on the column
    fragColor = vec4(b / 3.14159265 + 0.5, 0.5, 0.5, 1.0);
}
