// expect: reserved by WebGL
float _webgl_offset(float x) // ERROR
{
    return x + 0.5;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(_webgl_offset(0.0));
}
