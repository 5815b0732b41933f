// expect: cannot be declared 'void'
void f()
{
    void x; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
