// expect: is not a type
void g()
{
    struct T { float a; };
}
void f()
{
    T t; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
