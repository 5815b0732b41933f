// expect: already declared in this scope
struct S { float a; };
struct S { float b; }; // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
