// Image.glsl (Shadertoy tab: Image) - Lab 4, part 6: multiple lights
// Purpose: four lights over a gradient background:
//          C = I_A C_A + sum over i of (I_Di C_D + I_Si C_S) C_Li.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Blinn-Phong halfway vector after James F. Blinn, Models of Light Reflection for Computer Synthesized Pictures, SIGGRAPH 1977

// Gradient background: a dark blue floor tone fading up to a lighter sky tone.
const vec3 kBackgroundBottom = vec3(0.05, 0.05, 0.12);
const vec3 kBackgroundTop = vec3(0.35, 0.45, 0.65);
// Global ambient light I_A C_A: a weak bluish fill, so no surface is ever pure black.
const float kAmbientIntensity = 0.2;
const vec3 kAmbientColor = vec3(0.35, 0.45, 1.0);
// White specular color C_S: highlights show the light's own color, like glossy plastic.
const vec3 kSpecularColor = vec3(1.0);
// Blinn-Phong exponent alpha' = 4 alpha with alpha = 32, fixed at compile time.
const float kAlphaPrime = 4.0 * 32.0;
// Four point lights around the spheres: each adds its own colored diffuse and highlight.
const sPointLight kLights[kLightCount] = sPointLight[kLightCount](
    sPointLight(vec3(1.3, 0.75, -2.5), vec3(1.0, 0.5, 0.2), 9.0),  // red-orange key, above right of the eye
    sPointLight(vec3(-3.0, 1.5, -4.0), vec3(0.25, 0.5, 1.0), 5.0), // blue fill from the upper left
    sPointLight(vec3(0.5, -2.2, -3.5), vec3(0.3, 1.0, 0.4), 4.0),  // green bounce from below
    sPointLight(vec3(1.0, 3.0, -9.5), vec3(1.0, 0.9, 1.0), 6.0));  // white rim light, behind and above

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // viewing-plane point kept: its height also drives the background gradient
    vec2 viewport = calcViewport(fragCoord, iResolution.xy);
    sRay ray = calcRay(viewport);
    // vertical gradient behind the spheres: viewport y in [-1, 1] remapped to [0, 1]
    vec3 background = mix(kBackgroundBottom, kBackgroundTop, viewport.y * 0.5 + 0.5);
    // nearest surface point and its unit normal; hit is 1 on a sphere, 0 elsewhere
    vec3 position;
    vec3 normal;
    float hit = traceScene(ray, position, normal);
    // V points from the surface back to the eye, which is exactly -direction of the unit
    // ray that found the surface: no subtraction and no normalize needed
    vec3 viewDir = -ray.direction;
    // C = I_A C_A + sum of the lights: ambient is light-independent, so it stays outside the loop
    vec3 color = kAmbientIntensity * kAmbientColor + sumLights(kLights, position, normal, viewDir, normal * 0.5 + 0.5, kSpecularColor, kAlphaPrime);
    // branchless background selection with the hit mask
    fragColor = vec4(mix(background, color, hit), 1.0);
}
