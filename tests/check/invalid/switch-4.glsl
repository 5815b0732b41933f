// expect: already has a 'default'
void f(int i)
{
    switch (i)
    {
    default:
        break;
    default: // ERROR
        break;
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
