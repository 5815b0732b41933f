// expect: cannot multiply 'mat3' by 'vec2'
vec3 f(mat3 m, vec2 v)
{
    return m * v; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
