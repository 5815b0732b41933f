// expect: 'fooo' is not declared
float foo(float x) { return x; }
float f()
{
    return fooo(1.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
