// expect: returns 'vec3' but this value is 'vec4'
vec3 f()
{
    return vec4(1.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
