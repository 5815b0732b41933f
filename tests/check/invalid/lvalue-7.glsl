// expect: must be a variable
void f()
{
    float whole;
    float part = modf(1.5, 2.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
