// expect: greater than zero
const int N = 2;
float a[N - 2]; // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
