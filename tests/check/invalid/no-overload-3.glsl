// expect: is a variable, not a function
float g() { return 1.0; }
void f()
{
    float g = 2.0;
    float y = g(); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
