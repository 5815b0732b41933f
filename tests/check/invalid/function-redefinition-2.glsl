// expect: declared again with return type
float g(float x) { return x; }
int g(float x) { return 1; } // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
