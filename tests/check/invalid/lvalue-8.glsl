// expect: must be a variable
void g(out float x) { x = 1.0; }
void f()
{
    g(iTime); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
