// Image.glsl (Shadertoy tab: Image) - Lab 4, bonus: cel shading
// Purpose: cel shading: colored spheres in flat bands of light with hard highlights
//          and dark outlines where the surface turns away from the viewer.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Blinn-Phong halfway vector after James F. Blinn, Models of Light Reflection for Computer Synthesized Pictures, SIGGRAPH 1977
//   Cel shading after A. Lake, C. Marshall, M. Harris, M. Blackstein, Stylized Rendering Techniques for Scalable Real-Time 3D Animation, NPAR 2000

// Flat, light backdrop like a cartoon cel.
const vec3 kBackground = vec3(0.85, 0.9, 0.95);
// Ambient share of the surface color: the darkest band is never black.
const float kAmbientIntensity = 0.25;
// Outline: where N.V falls below this, the surface is seen edge-on and is inked.
const float kOutline = 0.3;
// Blinn-Phong exponent alpha' = 4 alpha with alpha = 32, fixed at compile time.
const float kAlphaPrime = 4.0 * 32.0;
// Key light above right of the viewer and a cooler fill from the left.
const sPointLight kLights[kLightCount] = sPointLight[kLightCount](
    sPointLight(vec3(1.3, 1.5, -2.5), vec3(1.0, 0.95, 0.9), 12.0), // warm key light
    sPointLight(vec3(-3.0, 0.5, -4.0), vec3(0.3, 0.35, 0.5), 6.0)); // dim cool fill light

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
    // banded diffuse light and flat highlights from all lights
    vec3 diffuseSum;
    vec3 specularSum;
    celLights(kLights, position, normal, viewDir, kAlphaPrime, diffuseSum, specularSum);
    // the surface keeps its color in every band; highlights are white-ish light on top
    vec3 color = (kAmbientIntensity + diffuseSum) * albedo + specularSum;
    // ink the silhouette: step is 0 where the surface is nearly edge-on to the viewer
    float ink = step(kOutline, dot(normal, viewDir));
    fragColor = vec4(mix(kBackground, color * ink, hit), 1.0);
}
