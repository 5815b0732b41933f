// expect: only the std140 layout
layout(packed) uniform Lights // ERROR
{
    vec4 lightColor;
};

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = lightColor;
}
