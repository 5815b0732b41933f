// Image.glsl (Shadertoy tab: Image) - Lab 4, part 1: spheres, ray-traced
// Purpose: ray-trace the sphere scene and show each surface normal as a color on a
//          solid grey background: the geometry every later lighting part shades.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/

// Solid grey behind the spheres, as in the assignment's figure.
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
    // remap the normal from [-1, 1] to [0, 1] so every direction is a visible color
    vec3 normalColor = normal * 0.5 + 0.5;
    // branchless background selection with the hit mask
    fragColor = vec4(mix(kBackground, normalColor, hit), 1.0);
}
