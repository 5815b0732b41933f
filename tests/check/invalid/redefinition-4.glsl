// expect: already declared in this scope
float g(float a, float a) // ERROR
{
    return a;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
