// integer division by a constant zero
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    int i = int(fragCoord.x);
    int k = i / 0;  // undefined: division-by-zero
    int m = i % 0;  // undefined: division-by-zero
    fragColor = vec4(float(k & 255) / 255.0, float(m & 255) / 255.0, 0.5, 1.0);
}
