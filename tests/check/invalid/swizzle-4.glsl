// expect: no scalar swizzles
float f(float x)
{
    return x.x; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
