// an out parameter read before it is written, as a square root's argument
float lit(out float k, in float x)
{
    return sqrt(k - 0.05) + x;  // undefined: out-parameter
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float k;
    float v = lit(k, fragCoord.x / iResolution.x);
    fragColor = vec4(vec3(v), 1.0);
}
