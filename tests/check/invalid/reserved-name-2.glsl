// expect: names starting with 'gl_'
void f()
{
    vec4 gl_FragColor = vec4(1.0); // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
