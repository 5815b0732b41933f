// expect: both 'const' and 'out'
void f(const out float x) // ERROR
{
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
