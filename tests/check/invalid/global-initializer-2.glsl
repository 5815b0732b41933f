// expect: must be a constant expression
float a = 1.0;
float b = a; // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
