// expect: before its first 'case'
void f(int i)
{
    switch (i)
    {
        i = 2; // ERROR
    case 0:
        break;
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
