// expect: has no return statement
float f(float x) // ERROR
{
    x += 1.0;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
