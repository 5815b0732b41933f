// expect: in an earlier declaration
void g(in float x);
void g(out float x) { x = 1.0; } // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
