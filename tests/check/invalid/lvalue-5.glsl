// expect: function call's result
float g() { return 1.0; }
void f()
{
    g() = 1.0; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
