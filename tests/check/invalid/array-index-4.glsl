// expect: index must be an int or uint
float f()
{
    float a[3];
    return a[1.0]; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
