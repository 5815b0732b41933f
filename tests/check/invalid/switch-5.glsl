// expect: must be followed by a statement
void f(int i)
{
    switch (i)
    {
    case 0:
        break;
    case 1: // ERROR
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
