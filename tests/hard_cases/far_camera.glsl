// Hard case: a camera far from the origin (float32 cancellation).
// Camera and sphere both near x = 1e5, where float32 steps are 1/128: ro - centre cancels, the
// image is blocky and banded, and any renderer that computes in float64, fuses a multiply-add
// or reassociates differs. llvmpipe forms no FMA, so float32 step by step matches bit for bit.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 offset = vec3(1.0e5, -3.0e4, 7.0e4);
    vec3 ro = offset + vec3(0.3 * sin(iTime), 0.0, -3.0);
    vec3 rd = normalize(vec3(uv, 1.5));
    vec3 centre = offset + vec3(0.0, 0.0, 0.5);
    vec3 oc = ro - centre;
    float b = dot(oc, rd);
    float h = b * b - (dot(oc, oc) - 1.0);
    vec3 col = vec3(0.2, 0.3, 0.4) + 0.1 * rd;
    if (h >= 0.0) {
        float t = -b - sqrt(h);
        vec3 p = ro + t * rd;                 // 1e5 + small: the small part is quantised to 1/128
        vec3 n = normalize(p - centre);
        col = vec3(0.5) + 0.5 * n;
        col *= 0.5 + 0.5 * fract(p.x * 16.0); // exposes the quantisation of p
    }
    fragColor = vec4(col, 1.0);
}
