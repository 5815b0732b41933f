// expect: different types
float f(bool b)
{
    return b ? 1.0 : 2; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
