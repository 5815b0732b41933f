// expect: constant integer expression
void f(int i, int j)
{
    switch (i)
    {
    case j: // ERROR
        break;
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
