// expect: cannot initialise 'a' of type 'float[2]'
void f()
{
    float a[2] = float[3](1.0, 2.0, 3.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
