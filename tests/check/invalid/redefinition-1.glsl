// expect: already declared in this scope
void f()
{
    float a = 1.0;
    float a = 2.0; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
