// expect: 'colr' is not declared
vec3 f()
{
    vec3 color = vec3(1.0);
    return colr; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
