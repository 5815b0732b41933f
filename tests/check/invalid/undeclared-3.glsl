// expect: 'i' is not declared
void f()
{
    for (int i = 0; i < 3; i++) { }
    int j = i; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
