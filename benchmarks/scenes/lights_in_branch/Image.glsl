// Benchmark scene: the four-sphere, four-light Blinn-Phong scene of lights_array, with its light
// array declared at the top of the shading code and filled with constants inside the branch that
// only the pixels hitting a sphere take (`PointLight L[4]; if (tbest < 1e8) { L[0] =
// PointLight(...); ... }`), as submissions often do. Every lane that writes a light writes the
// same value and only those lanes read it, so a renderer that sees uniformity computes the
// lights once per frame, not once per pixel under the branch's mask.

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

    float tbest = 1e9;
    int hit = 0;
    for (int i = 0; i < 4; i++) {
        float t = hitSphere(ro, rd, centers[i], 0.85);
        if (t > 0.0 && t < tbest) {
            tbest = t;
            hit = i;
        }
    }
    vec3 col = vec3(0.15, 0.18, 0.25);
    PointLight L[4];
    if (tbest < 1e8) {
        L[0] = PointLight(vec3(-4.0, 4.0, -4.0), vec3(1.0, 0.9, 0.8), 1.0);
        L[1] = PointLight(vec3(4.0, 4.0, -4.0), vec3(0.6, 0.7, 1.0), 1.0);
        L[2] = PointLight(vec3(0.0, -4.0, -3.0), vec3(0.5, 0.5, 0.5), 1.0);
        L[3] = PointLight(vec3(2.0 * cos(iTime), 0.0, -8.0), vec3(0.4, 0.4, 0.4), 1.0);
        vec3 albedo = 0.5 + 0.4 * cos(vec3(0.0, 2.0, 4.0) + float(hit) * 1.7);
        vec3 p = ro + rd * tbest;
        vec3 n = normalize(p - centers[hit]);
        vec3 v = -rd;
        col = 0.05 * albedo;
        for (int k = 0; k < 4; k++) {
            col += blinnPhong(p, n, v, albedo, L[k]);
        }
        col = pow(col, vec3(1.0 / 2.2));
    }
    fragColor = vec4(col, 1.0);
}
