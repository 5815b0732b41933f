// A plane facing the camera, lit by a point light that lies in the plane itself: at the pixel
// under the light, the vector to the light is zero and normalize() makes NaN (the probe demo).
const vec2 kLightPixel = vec2(200.5, 120.5);

// The point of the plane z = 0 seen at a pixel (the plane fills the view, 1 unit = the height).
vec3 planePoint(vec2 pixel)
{
    return vec3((pixel - 0.5 * iResolution.xy) / iResolution.y, 0.0);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 p = planePoint(fragCoord);
    vec3 light = planePoint(kLightPixel);
    vec3 toLight = normalize(light - p);
    // half-Lambert: the surface tilts towards the light's side
    float wrap = dot(normalize(vec3(0.3, 0.2, 1.0)), toLight) * 0.5 + 0.5;
    float dist = length(light - p);
    float falloff = 1.0 / (1.0 + 8.0 * dist * dist);
    fragColor = vec4(vec3(1.0, 0.8, 0.5) * wrap * falloff, 1.0);
}
