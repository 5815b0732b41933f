// Hard case: rays tangent to a sphere, grazing its edge.
// The discriminant h = b*b - c of the ray-sphere quadratic is ~0 along the silhouette, where one
// float32 rounding decides hit or miss, and sqrt(h) of a slightly negative h is NaN. The blue
// channel takes sqrt(h) unguarded, so both renderers must agree on the sign of h bit for bit.
float hitSphere(vec3 ro, vec3 rd, vec3 centre, float radius, out float h)
{
    vec3 oc = ro - centre;
    float b = dot(oc, rd);
    h = b * b - (dot(oc, oc) - radius * radius);
    if (h < 0.0) return -1.0;
    return -b - sqrt(h);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 ro = vec3(0.0, 0.0, -3.0);
    vec3 rd = normalize(vec3(uv, 1.5));
    // Whole steps of iTime only, so the radius is the same float in both renderers.
    float radius = 0.8 + 0.05 * floor(iTime);
    float h;
    float t = hitSphere(ro, rd, vec3(0.0), radius, h);
    vec3 col = vec3(0.1, 0.1, 0.2);
    if (t > 0.0) {
        vec3 n = normalize(ro + t * rd);
        col = 0.5 + 0.5 * n;
    }
    col.b += sqrt(h) * 4.0;  // NaN outside the sphere, ~0 on the silhouette
    fragColor = vec4(col, 1.0);
}
