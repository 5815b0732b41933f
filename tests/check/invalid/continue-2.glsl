// expect: 'continue' is only allowed inside a loop
void f()
{
    continue; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
