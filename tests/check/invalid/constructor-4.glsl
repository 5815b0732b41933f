// expect: 'sampler2D' cannot be constructed
void f()
{
    vec4 c = texture(sampler2D(0), vec2(0.0)); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
