// expect: must be a constant expression
vec4 f(int k)
{
    return textureOffset(iChannel0, vec2(0.0), ivec2(k)); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
