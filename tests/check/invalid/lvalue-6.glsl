// expect: (a const parameter)
float f(const float x)
{
    x = 2.0; // ERROR
    return x;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
