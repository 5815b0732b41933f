// expect: cannot assign 'int' to 'float'
void f()
{
    float x;
    x = 3; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
