// Image.glsl (Shadertoy tab: Image) - Lab 4, part 3: Lambert diffuse coefficient
// Purpose: show the diffuse coefficient k_D = max(0, N.L) in every color channel for
//          a light just above and to the right of the viewer.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/

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
    // k_D only: how squarely each surface point faces the light, shown as grey levels
    float kD = diffuseCoefficient(normal, lightDirection(light, position));
    // branchless background selection with the hit mask
    fragColor = vec4(mix(kBackground, vec3(kD), hit), 1.0);
}
