// expect: reserved by WebGL
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float webgl_scale = 2.0; // ERROR
    fragColor = vec4(webgl_scale);
}
