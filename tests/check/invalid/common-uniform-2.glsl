// expect: without iResolution; pass it as a parameter from mainImage
// tab: Common
vec2 uv(vec2 fragCoord)
{
    return fragCoord / iResolution.xy; // ERROR
}
