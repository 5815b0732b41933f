// expect: only the std140 layout
layout(std140, shared) uniform Lights // ERROR
{
    vec4 lightColor;
};

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = lightColor;
}
