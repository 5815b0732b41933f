// expect: must be a bool, not 'bvec2'
void f(vec2 a)
{
    for (; lessThan(a, vec2(1.0)); ) // ERROR
    {
    }
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
