// expect: repeats a component
void f()
{
    vec2 v;
    v.xx = vec2(1.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
