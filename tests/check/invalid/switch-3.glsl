// expect: appears twice
void f(int i)
{
    switch (i)
    {
    case 0:
    case 0: // ERROR
        break;
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
