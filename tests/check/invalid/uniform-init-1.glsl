// expect: cannot have an initializer
uniform float gain = 1.0; // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
