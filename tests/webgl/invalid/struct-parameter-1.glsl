// expect: a parameter's type cannot define a struct
float brightness(struct Light { vec3 color; } light) // ERROR
{
    return dot(light.color, vec3(0.299, 0.587, 0.114));
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(vec3(0.5), 1.0);
}
