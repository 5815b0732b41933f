// expect: no matching overload
float f(float x)
{
    return pow(x, 2); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
