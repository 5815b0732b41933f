// Hard case: pixels exactly on a silhouette.
// Orthographic rays through pixel centres against a circle of whole-pixel radius 25 centred on a
// pixel centre: every quantity is a whole number, so h = r*r - dot(d, d) is exactly 0 at the 20
// pixel centres (+-25, 0), (0, +-25), (+-7, +-24), (+-24, +-7), (+-15, +-20), (+-20, +-15): sqrt(h) is 0 there,
// NaN outside, and `h == 0.0` lights those pixels alone.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 centre = floor(iResolution.xy * 0.5) + 0.5;  // a pixel centre
    vec2 d = fragCoord - centre;                       // whole numbers
    float radius = 25.0;
    float h = radius * radius - dot(d, d);
    float z = sqrt(h);                                 // NaN where h < 0
    // Guarded: normalize of a vector with a NaN component is NaN in IEEE arithmetic but finite
    // (garbage) on llvmpipe, and GLSL does not require NaN propagation.
    vec3 n = normalize(vec3(d, sqrt(max(h, 0.0))));    // (d, 0)/25 on the silhouette
    fragColor = vec4(z / radius, h == 0.0 ? 1.0 : 0.0, 0.5 + 0.5 * n.x, 1.0);
}
