// expect: WebGL does not allow '?:' on structs
struct Light
{
    vec3 color;
};

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    Light warm = Light(vec3(1.0, 0.8, 0.6));
    Light cold = Light(vec3(0.6, 0.8, 1.0));
    Light used = fragCoord.x > 100.0 ? warm : cold; // ERROR
    fragColor = vec4(used.color, 1.0);
}
