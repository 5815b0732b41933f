// a float value divided by a constant zero (a zero known only at run time divides as IEEE)
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 v = vec3(fragCoord.x - 16.0) / 0.0;  // undefined: division-by-zero
    float w = fragCoord.y - 9.0;
    w /= vec2(0.0, 2.0).x;  // undefined: division-by-zero
    float r = (fragCoord.y - 9.5) / floor(fragCoord.x * 0.01);
    const float big = 1.0 / 0.0;
    fragColor = vec4(fragCoord.x < 16.0 ? vec3(0.5) : v * 0.01, w + min(r, big));
}
