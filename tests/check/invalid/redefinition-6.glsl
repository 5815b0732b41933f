// expect: already declared in this scope
float S;
struct S { float a; }; // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
