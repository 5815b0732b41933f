// expect: is a function; call it
float g() { return 1.0; }
float f()
{
    return g; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
