// expect: WebGL does not allow '?:' on arrays
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float a[2] = float[2](0.0, 1.0);
    float b[2] = float[2](1.0, 0.0);
    float c[2] = fragCoord.x > 100.0 ? a : b; // ERROR
    fragColor = vec4(c[0], c[1], 0.0, 1.0);
}
