// expect: cannot define another struct
struct A
{
    struct B { float x; } b; // ERROR
};

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
