// expect: already declared in this scope
void f()
{
    for (int i = 0; i < 3; i++)
    {
        int i = 1; // ERROR
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
