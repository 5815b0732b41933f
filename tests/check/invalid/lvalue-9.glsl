// expect: is const
const float K = 1.0;
void f()
{
    K++; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
