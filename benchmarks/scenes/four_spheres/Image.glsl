// Benchmark scene: four ray-traced spheres lit by four point lights (Blinn-Phong).
// SPHERE_RADIUS sizes the spheres, which stay where they are (the benchmark changes it to vary
// how much of the image they cover: 0.7 covers 10% of an 800x450 frame, 2.8 covers 99%;
// background pixels should cost almost nothing).
#define SPHERE_RADIUS 0.85

const vec3 BACKGROUND = vec3(0.15, 0.18, 0.25);  // already display-encoded

struct Light { vec3 pos; vec3 color; };

float hitSphere(vec3 ro, vec3 rd, vec3 c, float r) {
    vec3 oc = ro - c;
    float b = dot(oc, rd);
    float h = b * b - (dot(oc, oc) - r * r);
    if (h < 0.0) return -1.0;
    return -b - sqrt(h);
}

vec3 blinnPhong(vec3 p, vec3 n, vec3 v, vec3 albedo, Light l) {
    vec3 toL = l.pos - p;
    float dist = length(toL);
    vec3 ld = toL / dist;
    vec3 h = normalize(ld + v);
    float diff = max(dot(n, ld), 0.0);
    float spec = pow(max(dot(n, h), 0.0), 48.0);
    float att = 1.0 / (1.0 + 0.05 * dist * dist);
    return (albedo * diff + vec3(0.6) * spec) * l.color * att;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 ro = vec3(0.0, 0.0, -6.0);
    vec3 rd = normalize(vec3(uv, 2.0));

    vec3 centers[4] = vec3[4](vec3(-1.7, 0.9, 0.0), vec3(1.7, 0.9, 0.0), vec3(-1.7, -0.9, 0.0), vec3(1.7, -0.9, 0.0));
    vec3 albedos[4] = vec3[4](vec3(0.9, 0.2, 0.2), vec3(0.2, 0.9, 0.3), vec3(0.2, 0.4, 0.9), vec3(0.9, 0.8, 0.2));
    Light lights[4] = Light[4](Light(vec3(-4.0, 4.0, -4.0), vec3(1.0, 0.9, 0.8)),
                               Light(vec3(4.0, 4.0, -4.0), vec3(0.6, 0.7, 1.0)),
                               Light(vec3(0.0, -4.0, -3.0), vec3(0.5, 0.5, 0.5)),
                               Light(vec3(0.0, 0.0, -8.0), vec3(0.4, 0.4, 0.4)));

    float best = 1e9;
    int hit = -1;
    for (int i = 0; i < 4; i++) {
        float t = hitSphere(ro, rd, centers[i], SPHERE_RADIUS);
        if (t > 0.0 && t < best) { best = t; hit = i; }
    }
    vec3 col = BACKGROUND;
    if (hit >= 0) {
        vec3 p = ro + rd * best;
        vec3 n = normalize(p - centers[hit]);
        vec3 v = -rd;
        col = 0.05 * albedos[hit];
        for (int k = 0; k < 4; k++) {
            col += blinnPhong(p, n, v, albedos[hit], lights[k]);
        }
        col = pow(col, vec3(1.0 / 2.2));  // gamma only where there is lighting to correct
    }
    fragColor = vec4(col, 1.0);
}
