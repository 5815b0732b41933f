// a global set to a constant inside a march loop on some paths only (an edge found between
// steps), read by mainImage on every pixel: its value on entry is undefined
float edge;

float march(in vec2 uv)
{
    float d = 0.0;
    float last = 1e10;
    for (int i = 0; i < 16; i++) {
        float s = length(uv - vec2(0.5)) - 0.3 + 0.1 * sin(d * 6.0);
        if (last < 0.05 && s > last + 0.001) {
            edge = 1.0;
        }
        last = min(last, s);
        d += 0.1;
    }
    return d;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy;
    vec3 col = vec3(uv, march(uv) * 0.5);
    col = mix(col, vec3(0.3), edge);  // undefined: uninitialized-global
    fragColor = vec4(col, 1.0);
}
