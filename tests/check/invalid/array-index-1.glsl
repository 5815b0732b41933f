// expect: out of range
void f()
{
    float a[3];
    a[3] = 1.0; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
