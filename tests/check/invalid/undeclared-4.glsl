// expect: 'y' is not declared
void f()
{
    {
        float y = 1.0;
    }
    float z = y; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
