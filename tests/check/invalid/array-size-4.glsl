// expect: needs a size or an initializer
void f()
{
    float a[]; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
