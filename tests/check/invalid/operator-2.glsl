// expect: relational operators need numeric scalars
bool f(vec2 a, vec2 b)
{
    return a < b; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
