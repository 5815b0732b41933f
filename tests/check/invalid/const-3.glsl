// expect: not a constant expression
float f(float x)
{
    const float y = x; // ERROR
    return y;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
