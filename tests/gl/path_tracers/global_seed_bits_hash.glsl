// A small path tracer in the shape of "ray tracing in one weekend" ports: a global seed passed
// to an inout parameter, advanced by `seed += 0.1` inside a constructor's arguments, whose bits
// (floatBitsToUint) feed an integer hash; one sample, five bounces.
uint baseHash(uvec2 p) {
    p = 1103515245U * ((p >> 1U) ^ (p.yx));
    uint h32 = 1103515245U * ((p.x) ^ (p.y >> 3U));
    return h32 ^ (h32 >> 16);
}

float g_seed;

vec2 hash2(inout float seed) {
    uint n = baseHash(floatBitsToUint(vec2(seed += 0.1, seed += 0.1)));
    uvec2 rz = uvec2(n, n * 48271U);
    return vec2(rz.xy & uvec2(0x7fffffffU)) / float(0x7fffffff);
}

vec3 randomInUnitSphere() {
    vec2 h = hash2(g_seed) * vec2(2.0, 6.28318530718) - vec2(1.0, 0.0);
    float r = sqrt(1.0 - h.x * h.x);
    return vec3(r * cos(h.y), r * sin(h.y), h.x) * pow(hash2(g_seed).x, 1.0 / 3.0);
}

float sphere(vec3 ro, vec3 rd, vec4 sph) {
    vec3 oc = ro - sph.xyz;
    float b = dot(oc, rd);
    float h = b * b - dot(oc, oc) + sph.w * sph.w;
    if (h < 0.0) return -1.0;
    return -b - sqrt(h);
}

vec3 trace(vec3 ro, vec3 rd) {
    vec3 att = vec3(1.0);
    for (int i = 0; i < 5; i++) {
        float t = sphere(ro, rd, vec4(0.0, 0.0, -1.0, 0.5));
        float g = sphere(ro, rd, vec4(0.0, -100.5, -1.0, 100.0));
        vec3 c = vec3(0.0, 0.0, -1.0);
        if (g > 0.001 && (t < 0.001 || g < t)) {
            t = g;
            c = vec3(0.0, -100.5, -1.0);
        }
        if (t < 0.001) {
            return att * mix(vec3(1.0), vec3(0.5, 0.7, 1.0), 0.5 * rd.y + 0.5);
        }
        ro += t * rd;
        vec3 n = normalize(ro - c);
        rd = normalize(n + randomInUnitSphere());
        att *= 0.5;
    }
    return vec3(0.0);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    g_seed = float(baseHash(floatBitsToUint(fragCoord))) / float(0xffffffffU) + iTime;
    vec2 of = hash2(g_seed);
    vec2 uv = (fragCoord + of) / iResolution.xy;
    vec3 rd = normalize(vec3((uv * 2.0 - 1.0) * vec2(iResolution.x / iResolution.y, 1.0), -1.0));
    vec3 col = trace(vec3(0.0), rd);
    fragColor = vec4(sqrt(col), 1.0);
}
