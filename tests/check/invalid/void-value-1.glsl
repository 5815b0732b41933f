// expect: cannot initialise 'a' of type 'float' with a value of type 'void'
void g() { }
void f()
{
    float a = g(); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
