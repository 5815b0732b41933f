// expect: names containing '__' are reserved
struct Light
{
    vec3 color;
    float __power; // ERROR
};

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    Light light = Light(vec3(1.0, 0.9, 0.8), 0.5);
    fragColor = vec4(light.color * light.__power, 1.0);
}
