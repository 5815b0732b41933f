// Image.glsl (Shadertoy tab: Image) - Lab 4, part 4: Phong specular coefficient
// Purpose: show the specular coefficient k_S = max(0, V.R) in every color channel:
//          where the light's mirror reflection points at the eye.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Phong reflection after Bui Tuong Phong, Illumination for Computer Generated Pictures, CACM 18(6), 1975

// Solid grey behind the spheres, as in the assignment's figures.
const vec3 kBackground = vec3(0.5);

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
    // V points from the surface back to the eye, which is exactly -direction of the unit
    // ray that found the surface: no subtraction and no normalize needed
    vec3 viewDir = -ray.direction;
    // k_S only: a broad, unfocused highlight before any exponent is applied
    float kS = specularCoefficient(normal, lightDirection(light, position), viewDir);
    // branchless background selection with the hit mask
    fragColor = vec4(mix(kBackground, vec3(kS), hit), 1.0);
}
