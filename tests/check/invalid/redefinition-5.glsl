// expect: already declared by Shadertoy as a uniform
float iTime = 1.0; // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
