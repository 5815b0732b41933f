// expect: beyond the 2 components
float f(vec2 v)
{
    return v.z; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
