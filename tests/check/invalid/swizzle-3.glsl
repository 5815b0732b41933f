// expect: more than 4 components
vec4 f(vec4 v)
{
    return v.xyzwx; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
