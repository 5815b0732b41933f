// Hard case: a light exactly at the surface point, so L = normalize(light - P) = normalize(vec3(0)).
// A plane z = 0 with P = (fragCoord, 0); light 1 sits on the plane at one pixel centre (L is the
// zero vector there: NaN), light 2 hovers above it. The red channel is Lambert with max(), which
// turns NaN into 0 on llvmpipe (IEEE maxNum); green is the raw length of L (NaN at that pixel);
// blue is 1/d^2 attenuation (+Inf at that pixel); normalize(float 0) is sign(0) = 0.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 P = vec3(fragCoord, 0.0);
    vec3 N = vec3(0.0, 0.0, 1.0);
    vec3 light1 = vec3(floor(iResolution.xy * 0.5) + 0.5, 0.0);
    vec3 light2 = light1 + vec3(20.0 * sin(iTime), 0.0, 15.0);
    vec3 L1 = normalize(light1 - P);
    vec3 L2 = normalize(light2 - P);
    float lambert = max(dot(N, L1), 0.0) + max(dot(N, L2), 0.0);
    vec3 d = light1 - P;
    float attenuation = 100.0 / dot(d, d);
    float s = normalize(P.x - light1.x);
    fragColor = vec4(lambert, length(L1) * 0.5 + 0.25 * s, attenuation, 1.0);
}
