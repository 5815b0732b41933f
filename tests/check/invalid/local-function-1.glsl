// expect: cannot be declared inside a function
void f()
{
    float h(float); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
