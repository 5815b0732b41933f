// expect: cannot be applied to 'float'
float f(float a)
{
    return a & 1.0; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
