// Image.glsl (Shadertoy tab: Image) - Lab 4, bonus: spot lights
// Purpose: several spot lights with smooth cone edges sweeping over the spheres,
//          in a dark scene so the cones read clearly; iTime is read here and passed down.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Blinn-Phong halfway vector after James F. Blinn, Models of Light Reflection for Computer Synthesized Pictures, SIGGRAPH 1977
//   Spot-light cone falloff after Joey de Vries, LearnOpenGL, Light casters, https://learnopengl.com/Lighting/Light-casters

// Dark stage behind the spheres, so only the cones light the scene.
const vec3 kBackgroundBottom = vec3(0.01, 0.01, 0.02);
const vec3 kBackgroundTop = vec3(0.06, 0.06, 0.1);
// Faint ambient I_A C_A: just enough to see the spheres outside the cones.
const vec3 kAmbient = 0.04 * vec3(0.35, 0.45, 1.0);
// White specular color C_S: highlights show the light's own color.
const vec3 kSpecularColor = vec3(1.0);
// Blinn-Phong exponent alpha' = 4 alpha with alpha = 32, fixed at compile time.
const float kAlphaPrime = 4.0 * 32.0;

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
    // the spots' aim at this moment: the uniform is read here and passed down
    sSpotLight spots[kSpotCount];
    aimSpotLights(iTime, spots);
    // C = I_A C_A + sum of the spot lights
    vec3 color = kAmbient + sumSpotLights(spots, position, normal, viewDir, albedo, kSpecularColor, kAlphaPrime);
    // branchless background selection with the hit mask
    fragColor = vec4(mix(background, color, hit), 1.0);
}
