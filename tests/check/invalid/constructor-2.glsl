// expect: too many arguments
vec2 f()
{
    return vec2(1.0, 2.0, 3.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
