// A seed passed down by `inout` into a bounce loop that can be left early and draws its next
// direction in one of two arms of an `if` (uniform or cosine sampling), through a sin hash.
vec2 hash2(inout float seed) {
    return fract(sin(vec2(seed += 0.1, seed += 0.1)) * vec2(43758.5453123, 22578.1459123));
}

vec3 uniformSample(vec3 n, inout float seed) {
    vec2 u = hash2(seed);
    float r = sqrt(1.0 - u.x * u.x);
    float phi = 6.2831853 * u.y;
    vec3 b = normalize(cross(n, vec3(0.0, 1.0, 1.0)));
    vec3 t = cross(b, n);
    return normalize(r * sin(phi) * b + u.x * n + r * cos(phi) * t);
}

vec3 cosineSample(vec3 n, inout float seed) {
    vec2 u = hash2(seed);
    float r = sqrt(u.x);
    float theta = 6.2831853 * u.y;
    vec3 b = normalize(cross(n, vec3(0.0, 1.0, 1.0)));
    vec3 t = cross(b, n);
    return normalize(r * sin(theta) * b + sqrt(1.0 - u.x) * n + r * cos(theta) * t);
}

vec2 intersect(vec3 ro, vec3 rd, out vec3 normal) {
    vec2 res = vec2(1e20, -1.0);
    float t = -ro.y / rd.y;
    if (t > 1e-4) { res = vec2(t, 1.0); normal = vec3(0.0, 1.0, 0.0); }
    vec3 oc = ro - vec3(0.0, 1.0, 4.0);
    float b = dot(oc, rd);
    float h = b * b - dot(oc, oc) + 1.0;
    if (h > 0.0) {
        t = -b - sqrt(h);
        if (t > 1e-4 && t < res.x) { res = vec2(t, 2.0); normal = normalize(oc + t * rd); }
    }
    return res;
}

vec3 trace(vec3 ro, vec3 rd, bool uniformSampling, inout float seed) {
    vec3 col = vec3(1.0);
    for (int j = 0; j < 3; ++j) {
        vec3 normal;
        vec2 res = intersect(ro, rd, normal);
        if (res.y < -0.5) {
            return col;
        }
        ro += res.x * rd;
        if (uniformSampling) {
            rd = uniformSample(normal, seed);
            col *= 2.0 * dot(rd, normal);
        } else {
            rd = cosineSample(normal, seed);
        }
        col *= 0.7;
    }
    return vec3(0.0);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    float seed = p.x + p.y * 3.43121412313;
    vec2 jitter = hash2(seed) / iResolution.xy;
    vec3 rd = normalize(vec3(p + jitter, 2.0) - vec3(0.0, 0.5, 0.0));
    vec3 col = trace(vec3(0.0, 1.0, 0.0), rd, fragCoord.x < iResolution.x * 0.5, seed);
    fragColor = vec4(col, seed);
}
