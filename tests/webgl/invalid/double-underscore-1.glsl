// expect: names containing '__' are reserved
const float light__power = 2.0; // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(vec3(light__power * 0.25), 1.0);
}
