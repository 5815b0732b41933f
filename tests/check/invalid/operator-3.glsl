// expect: logical operators need bool
bool f(int a)
{
    return a && true; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
