// expect: 'mainImage' has the wrong parameters
void mainImage(out vec4 fragColor, in vec3 fragCoord)
{
    fragColor = vec4(0.0);
}
