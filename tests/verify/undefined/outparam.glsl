// an out parameter read before it is written: the colour is its value on entry
void shade(out vec3 c, in float x)
{
    c += vec3(x);  // undefined: out-parameter
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 col = vec3(0.25, 0.5, 0.75);
    shade(col, fragCoord.x / iResolution.x);
    fragColor = vec4(col, 1.0);
}
