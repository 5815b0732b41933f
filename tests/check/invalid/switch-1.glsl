// expect: needs an int or uint value
void f(float x)
{
    switch (x) // ERROR
    {
    default:
        break;
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
