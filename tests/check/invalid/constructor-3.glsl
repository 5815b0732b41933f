// expect: field 'a' is 'float'
struct S { float a; };
S f()
{
    return S(1); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
