// expect: shader input
in vec2 uv;
void f()
{
    uv = vec2(1.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
