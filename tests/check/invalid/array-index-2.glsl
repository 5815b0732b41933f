// expect: out of range
float f(vec3 v)
{
    return v[3]; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
