// expect: no matching overload for 'dot(vec3, vec2)'
float f(vec3 a, vec2 b)
{
    return dot(a, b); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
