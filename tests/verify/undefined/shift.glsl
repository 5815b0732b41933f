// shifts by constants out of range
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    int i = int(fragCoord.x) + 1;
    int a = i << 33;  // undefined: shift-out-of-range
    int b = i >> -1;  // undefined: shift-out-of-range
    fragColor = vec4(float(a & 255) / 255.0, float(b & 255) / 255.0, 0.5, 1.0);
}
