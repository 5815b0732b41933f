// expect: must be a constant expression
vec4 c = gl_FragCoord; // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
