// expect: is a built-in function
float sin(float x) { return x; } // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
