// expect: sampler types can only be uniforms
void f()
{
    sampler2D s; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
