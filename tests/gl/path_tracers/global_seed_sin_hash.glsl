// A small path tracer in the shape of many public ones: a global seed advanced by `seed += 0.1`
// inside a constructor's arguments, fed to a sin hash; four samples, four bounces.
float seed;

vec2 hash2() {
    return fract(sin(vec2(seed += 0.1, seed += 0.1)) * vec2(43758.5453123, 22578.1459123));
}

vec3 cosineDirection(vec3 n) {
    vec2 r = hash2();
    vec3 uu = normalize(cross(n, abs(n.y) > 0.5 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    vec3 vv = cross(uu, n);
    float ra = sqrt(r.y);
    float rx = ra * cos(6.2831 * r.x);
    float ry = ra * sin(6.2831 * r.x);
    float rz = sqrt(1.0 - r.y);
    return normalize(rx * uu + ry * vv + rz * n);
}

float sphere(vec3 ro, vec3 rd, vec4 sph) {
    vec3 oc = ro - sph.xyz;
    float b = dot(oc, rd);
    float h = b * b - dot(oc, oc) + sph.w * sph.w;
    if (h < 0.0) return -1.0;
    return -b - sqrt(h);
}

vec2 intersect(vec3 ro, vec3 rd) {
    vec2 res = vec2(1e10, -1.0);
    float t = sphere(ro, rd, vec4(0.0, 0.0, 0.0, 1.0));
    if (t > 0.0 && t < res.x) res = vec2(t, 1.0);
    t = sphere(ro, rd, vec4(0.0, -101.0, 0.0, 100.0));
    if (t > 0.0 && t < res.x) res = vec2(t, 2.0);
    return res;
}

vec3 trace(vec3 ro, vec3 rd) {
    vec3 col = vec3(0.0);
    vec3 att = vec3(1.0);
    for (int b = 0; b < 4; b++) {
        vec2 res = intersect(ro, rd);
        if (res.y < 0.0) {
            col += att * vec3(0.6, 0.7, 0.9);
            break;
        }
        vec3 pos = ro + res.x * rd;
        vec3 nor = res.y == 1.0 ? normalize(pos) : vec3(0.0, 1.0, 0.0);
        att *= res.y == 1.0 ? vec3(0.9, 0.4, 0.3) : vec3(0.6);
        ro = pos + nor * 0.001;
        rd = cosineDirection(nor);
    }
    return col;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    seed = iTime + iResolution.y * fragCoord.x / iResolution.x + fragCoord.y / iResolution.y;
    vec3 col = vec3(0.0);
    for (int a = 0; a < 4; a++) {
        vec2 of = hash2() - 0.5;
        vec2 p = (2.0 * (fragCoord + of) - iResolution.xy) / iResolution.y;
        col += trace(vec3(0.0, 0.0, 4.0), normalize(vec3(p, -2.0)));
        seed = mod(seed * 1.1234567893490423, 13.0);
    }
    fragColor = vec4(sqrt(col / 4.0), 1.0);
}
