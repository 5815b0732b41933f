// expect: has no 'mainImage' function
void mainImg(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
