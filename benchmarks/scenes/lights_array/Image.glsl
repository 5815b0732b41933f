// Benchmark scene: the four-sphere, four-light Blinn-Phong scene of four_spheres, with its
// lights built as most Lab 4 submissions build them: a local array of structs in mainImage,
// written element by element (`PointLight L[4]; L[0] = PointLight(...);`), after background
// pixels have left mainImage early. Every light is the same in every pixel, so a renderer that
// sees uniformity computes them once per frame, not per pixel under the mask of the pixels left.

struct PointLight { vec3 center; vec3 color; float intensity; };

float hitSphere(vec3 ro, vec3 rd, vec3 c, float r) {
    vec3 oc = ro - c;
    float b = dot(oc, rd);
    float h = b * b - (dot(oc, oc) - r * r);
    if (h < 0.0) return -1.0;
    return -b - sqrt(h);
}

vec3 blinnPhong(vec3 p, vec3 n, vec3 v, vec3 albedo, PointLight light) {
    vec3 toL = light.center - p;
    float dist = length(toL);
    vec3 ld = toL / dist;
    vec3 h = normalize(ld + v);
    float diff = max(dot(n, ld), 0.0);
    float spec = pow(max(dot(n, h), 0.0), 48.0);
    float att = light.intensity / (1.0 + 0.05 * dist * dist);
    return (albedo * diff + vec3(0.6) * spec) * light.color * att;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 ro = vec3(0.0, 0.0, -6.0);
    vec3 rd = normalize(vec3(uv, 2.0));
    vec3 centers[4];
    centers[0] = vec3(-1.7, 0.9, 0.0);
    centers[1] = vec3(1.7, 0.9, 0.0);
    centers[2] = vec3(-1.7, -0.9, 0.0);
    centers[3] = vec3(1.7, -0.9, 0.0);

    float best = 1e9;
    int hit = -1;
    for (int i = 0; i < 4; i++) {
        float t = hitSphere(ro, rd, centers[i], 0.85);
        if (t > 0.0 && t < best) { best = t; hit = i; }
    }
    if (hit < 0) {
        fragColor = vec4(0.15, 0.18, 0.25, 1.0);
        return;
    }
    PointLight L[4];
    L[0] = PointLight(vec3(-4.0, 4.0, -4.0), vec3(1.0, 0.9, 0.8), 1.0);
    L[1] = PointLight(vec3(4.0, 4.0, -4.0), vec3(0.6, 0.7, 1.0), 1.0);
    L[2] = PointLight(vec3(0.0, -4.0, -3.0), vec3(0.5, 0.5, 0.5), 1.0);
    L[3] = PointLight(vec3(2.0 * cos(iTime), 0.0, -8.0), vec3(0.4, 0.4, 0.4), 1.0);
    vec3 albedos[4];
    for (int i = 0; i < 4; i++) {
        albedos[i] = 0.5 + 0.4 * cos(vec3(0.0, 2.0, 4.0) + float(i) * 1.7);
    }

    vec3 p = ro + rd * best;
    vec3 n = normalize(p - centers[hit]);
    vec3 v = -rd;
    vec3 col = 0.05 * albedos[hit];
    for (int k = 0; k < 4; k++) {
        col += blinnPhong(p, n, v, albedos[hit], L[k]);
    }
    fragColor = vec4(pow(col, vec3(1.0 / 2.2)), 1.0);
}
