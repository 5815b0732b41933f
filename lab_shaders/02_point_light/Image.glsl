// Image.glsl (Shadertoy tab: Image) - Lab 4, part 2: point light
// Purpose: instance one point light in the scene and show where it is: a glow
//          sized by its intensity and tinted by its color, over the normal-colored spheres.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/

// Solid grey behind the spheres, as in the assignment's figures.
const vec3 kBackground = vec3(0.5);

// Marker radius per unit of light intensity, so a stronger light draws a bigger glow.
const float kMarkerScale = 0.012;

// Glow of the light as seen along a ray, from the squared distance between the light
// centre and the ray: no square root is needed to know how close the ray passes.
float lightMarker(in sRay ray, in sPointLight light)
{
    // split eye-to-light into its part along the unit ray and the perpendicular rest
    vec3 toLight = light.center - ray.origin;
    float along = dot(toLight, ray.direction);
    float perpSq = dot(toLight, toLight) - along * along;
    // glow radius scales with intensity: r^2 / (r^2 + p^2) is 1 on the centre, fading outward
    float size = kMarkerScale * light.intensity;
    float sizeSq = size * size;
    float glow = sizeSq / (sizeSq + perpSq);
    // squaring sharpens the fade to 1/p^4 so the halo does not tint the whole frame
    return glow * glow;
}

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // one ray per pixel through the viewing plane
    sRay ray = calcRay(calcViewport(fragCoord, iResolution.xy));
    // nearest surface point and its unit normal; hit is 1 on a sphere, 0 elsewhere
    vec3 position;
    vec3 normal;
    float hit = traceScene(ray, position, normal);
    // the scene's point light: above and to the right of the viewer, in front of the spheres
    sPointLight light = sPointLight(vec3(1.3, 0.75, -2.5), vec3(1.0, 0.9, 0.75), 5.0);
    // remap the normal from [-1, 1] to [0, 1] so every direction is a visible color
    vec3 normalColor = normal * 0.5 + 0.5;
    // the light sits between the eye and every sphere, so its glow is simply added on top
    vec3 color = mix(kBackground, normalColor, hit) + light.color * lightMarker(ray, light);
    fragColor = vec4(color, 1.0);
}
