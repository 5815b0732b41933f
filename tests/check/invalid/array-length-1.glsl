// expect: applies to arrays only
int f(vec3 v)
{
    return v.length(); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
