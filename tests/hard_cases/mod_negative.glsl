// Hard case: mod and fract of negative numbers. GLSL defines mod(x, y) = x - y*floor(x/y)
// (so mod(-7.5, 2) = 0.5 and the sign follows y), and fract(x) = x - floor(x) (fract(-0.25) =
// 0.75, fract(-1e-9) = 1.0 in float32). NumPy's fmod/remainder give other signs; the left half
// has negative x, the top half a negative y, and y = 0 on the middle row gives NaN.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 centre = floor(iResolution.xy * 0.5) + 0.5;
    float x = (fragCoord.x - centre.x) * 0.173 + iTime;
    float y = (centre.y - fragCoord.y) * 0.05;  // 0 on the middle row, negative above the centre
    float m = mod(x, y);
    float f = fract(x * 0.25);
    float tiny = fract(-1.0e-9 * fragCoord.x);  // 1.0: x - floor(x) rounds to 1
    fragColor = vec4(m / max(abs(y), 1.0), f, tiny * 0.5, 1.0);
}
