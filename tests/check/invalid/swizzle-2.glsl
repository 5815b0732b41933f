// expect: mixes the sets
vec2 f(vec4 v)
{
    return v.xg; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
