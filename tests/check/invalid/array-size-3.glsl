// expect: constant integer expression
void f()
{
    float a[iFrame]; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
