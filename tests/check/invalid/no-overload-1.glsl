// expect: no function 'g(int)'
float g(float x) { return x; }
float f()
{
    return g(1); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
