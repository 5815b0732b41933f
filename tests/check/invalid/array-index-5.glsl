// expect: out of range
const int N = 4;
float f()
{
    float a[N];
    return a[N]; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
