// Image.glsl (Shadertoy tab: Image) - Lab 4, bonus: animated lights
// Purpose: the final scene with its four lights moving in orbits and a figure eight
//          around the spheres; iTime is read here and passed down.
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
// The ambient term I_A C_A does not depend on the pixel: folded into one constant.
const vec3 kAmbient = kAmbientIntensity * kAmbientColor;

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // viewing-plane point kept: its height also drives the background gradient
    vec2 viewport = calcViewport(fragCoord, iResolution.xy);
    sRay ray = calcRay(viewport);
    // vertical gradient behind the spheres: viewport y in [-1, 1] remapped to [0, 1]
    vec3 background = mix(kBackgroundBottom, kBackgroundTop, viewport.y * 0.5 + 0.5);
    // nearest surface point, its unit normal and its own diffuse color C_D
    vec3 position;
    vec3 normal;
    vec3 albedo;
    float hit = traceScene(ray, position, normal, albedo); // 1 on a sphere, 0 on background
    // V points from the surface back to the eye, which is exactly -direction of the unit
    // ray that found the surface: no subtraction and no normalize needed
    vec3 viewDir = -ray.direction;
    // the lights' positions at this moment: the uniform is read here and passed down
    sPointLight lights[kLightCount];
    animateLights(iTime, lights);
    // C = I_A C_A + sum of the lights: ambient is light-independent, so it stays outside the loop
    vec3 color = kAmbient + sumLights(lights, position, normal, viewDir, albedo, kSpecularColor, kAlphaPrime);
    // the ray is unit length, so projecting the hit offset on it recovers the hit distance t
    float surfaceT = dot(position - ray.origin, ray.direction);
    // the lights' glows go on top of whatever they are in front of
    fragColor = vec4(mix(background, color, hit) + lightMarkers(lights, ray, surfaceT), 1.0);
}
