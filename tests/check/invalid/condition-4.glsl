// expect: must be a bool, not 'int'
void f(int i)
{
    do { } while (i); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
