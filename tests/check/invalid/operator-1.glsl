// expect: cannot add 'vec3' and 'vec2'
vec3 f(vec3 a, vec2 b)
{
    return a + b; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
