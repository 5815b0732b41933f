// expect: 'mainImage' has the wrong parameters
void mainImage(out vec4 fragColor)
{
    fragColor = vec4(0.0);
}
