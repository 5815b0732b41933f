// Image.glsl (Shadertoy tab: Image) - Lab 4, part 5: Blinn-Phong beside Phong
// Purpose: Blinn-Phong (left half, alpha' = 4 alpha) beside Phong (right half), same
//          scene and light, to compare the shape of their highlights.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Phong reflection after Bui Tuong Phong, Illumination for Computer Generated Pictures, CACM 18(6), 1975
//   Blinn-Phong halfway vector after James F. Blinn, Models of Light Reflection for Computer Synthesized Pictures, SIGGRAPH 1977

// Solid grey behind the spheres, as in the assignment's figures.
const vec3 kBackground = vec3(0.5);
// Global ambient light I_A C_A: a weak bluish fill, so no surface is ever pure black.
const float kAmbientIntensity = 0.2;
const vec3 kAmbientColor = vec3(0.35, 0.45, 1.0);
// White specular color C_S: highlights show the light's own color, like glossy plastic.
const vec3 kSpecularColor = vec3(1.0);
// Phong highlight exponent alpha; the Blinn-Phong half uses alpha' = 4 alpha.
const float kAlpha = 16.0;

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // each half is a small screen of half the width showing the scene, centred
    vec2 halfSize = iResolution.xy * vec2(0.5, 1.0);
    // side is 0 on the left half and 1 on the right; it shifts the pixel into its half
    float side = step(halfSize.x, fragCoord.x);
    sRay ray = calcRay(calcViewport(fragCoord - vec2(side * halfSize.x, 0.0), halfSize));
    // nearest surface point and its unit normal; hit is 1 on a sphere, 0 elsewhere
    vec3 position;
    vec3 normal;
    float hit = traceScene(ray, position, normal);
    // red-orange point light above and to the right of the viewer, in front of the spheres
    sPointLight light = sPointLight(vec3(1.3, 0.75, -2.5), vec3(1.0, 0.5, 0.2), 9.0);
    // V points from the surface back to the eye, which is exactly -direction of the unit
    // ray that found the surface: no subtraction and no normalize needed
    vec3 viewDir = -ray.direction;
    // left half Blinn-Phong (blinn = 1), right half Phong (blinn = 0); normal as C_D
    vec3 diffuse;
    vec3 specular;
    lightTerms(light, position, normal, viewDir, normal * 0.5 + 0.5, kSpecularColor, kAlpha, 1.0 - side, diffuse, specular);
    // C = I_A C_A + (I_D C_D + I_S C_S) C_L, the same formula for both models
    vec3 color = kAmbientIntensity * kAmbientColor + diffuse + specular;
    fragColor = vec4(mix(kBackground, color, hit), 1.0);
}
