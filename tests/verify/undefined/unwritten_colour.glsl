// the colour is written on the right half only: the left half's is undefined
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    if (fragCoord.x > 0.5 * iResolution.x) fragColor = vec4(0.2, 0.4, 0.6, 1.0);
}  // undefined: out-parameter-unwritten
