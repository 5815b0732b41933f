// expect: condition of '?:' must be a bool
float f(int i)
{
    return i ? 1.0 : 2.0; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
