// expect: read-only built-in variable
void f()
{
    gl_FragCoord = vec4(1.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
