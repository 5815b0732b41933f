// Hard case: constant factors reassociated. GLSL ES 3.00 has no `precise`, and Mesa's optimiser
// treats float multiplication as associative: in `k * 1e30 * 1e9` it folds 1e30 * 1e9, which is
// +Inf in float32, so llvmpipe returns +Inf for every k > 0; IEEE left-to-right evaluation gives
// the finite 1e39*k < 3.4e38 for k < 0.34. And `(k * 1e30) * g * 1e-30` keeps large g finite on
// llvmpipe (1e30 * 1e-30 folds to 1) where left to right overflows. Red is +Inf everywhere on
// llvmpipe but finite in the left third left to right; green is finite everywhere on llvmpipe
// but +Inf in the right 60% left to right: verify reports both as NaN/Inf mismatches.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float k = fragCoord.x / iResolution.x;
    float a = k * 1.0e30 * 1.0e9;
    float g = iResolution.y * 1.0e7;
    float b = (k * 1.0e30) * g * 1.0e-30;
    fragColor = vec4(a * 1.0e-38, b * 1.0e-9, 0.0, 1.0);
}
