// expect: write 2.0
float f(float x)
{
    return x * 2; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
