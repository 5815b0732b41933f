// expect: not a constant expression
const vec4 C = texture(iChannel0, vec2(0.0)); // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
