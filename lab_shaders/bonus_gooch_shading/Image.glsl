// Image.glsl (Shadertoy tab: Image) - Lab 4, bonus: Gooch shading
// Purpose: Gooch shading: colored spheres shaded from cool blue to warm yellow,
//          with highlights and black silhouette lines, on a light backdrop.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Blinn-Phong halfway vector after James F. Blinn, Models of Light Reflection for Computer Synthesized Pictures, SIGGRAPH 1977
//   Gooch shading after A. Gooch, B. Gooch, P. Shirley, E. Cohen, A Non-Photorealistic Lighting Model for Automatic Technical Illustration, SIGGRAPH 1998, https://users.cs.northwestern.edu/~ago820/SIG98/abstract.html

// Light grey backdrop, as in technical illustrations.
const vec3 kBackground = vec3(0.9);
// Outline: where N.V falls below this, the surface is seen edge-on and is inked.
const float kOutline = 0.25;
// Blinn-Phong exponent alpha' = 4 alpha with alpha = 32, fixed at compile time.
const float kAlphaPrime = 4.0 * 32.0;

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // one ray per pixel through the viewing plane
    sRay ray = calcRay(calcViewport(fragCoord, iResolution.xy));
    // nearest surface point, its unit normal and its own diffuse color C_D
    vec3 position;
    vec3 normal;
    vec3 albedo;
    float hit = traceScene(ray, position, normal, albedo); // 1 on a sphere, 0 on background
    // V points from the surface back to the eye, which is exactly -direction of the unit
    // ray that found the surface: no subtraction and no normalize needed
    vec3 viewDir = -ray.direction;
    // a white light above and to the right of the viewer sets the warm side
    sPointLight light = sPointLight(vec3(2.0, 2.5, -2.0), vec3(1.0), 10.0);
    vec3 color = goochShade(light, position, normal, viewDir, albedo, kAlphaPrime);
    // ink the silhouette: step is 0 where the surface is nearly edge-on to the viewer
    float ink = step(kOutline, dot(normal, viewDir));
    fragColor = vec4(mix(kBackground, color * ink, hit), 1.0);
}
