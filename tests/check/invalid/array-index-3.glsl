// expect: out of range
vec2 f(mat2 m)
{
    return m[2]; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
