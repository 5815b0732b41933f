// expect: not a constant expression
float g() { return 1.0; }
const float K = g(); // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
