// globals without initializers assigned on every path before they are read: a reset called
// first, an if/else in a helper, and a counting loop whose body runs; nothing is undefined
float edge;
vec3 tint;
float weights[3];

void reset()
{
    edge = 0.0;
}

void pick(in float x)
{
    if (x > 0.5) {
        tint = vec3(0.2, 0.4, 0.6);
    } else {
        tint = vec3(0.6, 0.4, 0.2);
    }
}

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
    reset();
    pick(uv.x);
    for (int i = 0; i < 3; i++) {
        weights[i] = float(i + 1) / 6.0;
    }
    vec3 col = vec3(uv, march(uv) * 0.5) * weights[2] + tint * weights[0];
    col = mix(col, vec3(0.3), edge);
    fragColor = vec4(col, 1.0);
}
