// expect: no implicit conversion
void f()
{
    uint u = 1; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
