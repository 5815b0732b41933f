// expect: must be a bool, not 'float'
void f(float x)
{
    while (x) // ERROR
    {
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
