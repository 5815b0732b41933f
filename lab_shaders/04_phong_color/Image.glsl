// Image.glsl (Shadertoy tab: Image) - Lab 4, part 4: Phong final color
// Purpose: the final Phong color C = I_A C_A + (I_D C_D + I_S C_S) C_L: red-orange
//          light, normal as diffuse color, white specular color, bluish ambient.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Phong reflection after Bui Tuong Phong, Illumination for Computer Generated Pictures, CACM 18(6), 1975

// Solid grey behind the spheres, as in the assignment's figures.
const vec3 kBackground = vec3(0.5);
// Global ambient light I_A C_A: a weak bluish fill, so no surface is ever pure black.
const float kAmbientIntensity = 0.2;
const vec3 kAmbientColor = vec3(0.35, 0.45, 1.0);
// White specular color C_S: highlights show the light's own color, like glossy plastic.
const vec3 kSpecularColor = vec3(1.0);
// Highlight exponent alpha: a medium-sized, plastic-looking highlight.
const float kAlpha = 32.0;

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // one ray per pixel through the viewing plane
    sRay ray = calcRay(calcViewport(fragCoord, iResolution.xy));
    // nearest surface point and its unit normal; hit is 1 on a sphere, 0 elsewhere
    vec3 position;
    vec3 normal;
    float hit = traceScene(ray, position, normal);
    // red-orange point light above and to the right of the viewer, in front of the spheres
    sPointLight light = sPointLight(vec3(1.3, 0.75, -2.5), vec3(1.0, 0.5, 0.2), 9.0);
    // V points from the surface back to the eye, which is exactly -direction of the unit
    // ray that found the surface: no subtraction and no normalize needed
    vec3 viewDir = -ray.direction;
    // C_D: the normal's gradient, so the diffuse falloff shows over a range of colors
    vec3 diffuseColor = normal * 0.5 + 0.5;
    // the light-dependent reflections I_D C_D C_L and I_S C_S C_L
    vec3 diffuse;
    vec3 specular;
    phongTerms(light, position, normal, viewDir, diffuseColor, kSpecularColor, kAlpha, diffuse, specular);
    // C = I_A C_A + (I_D C_D + I_S C_S) C_L: ambient needs no light, the rest is summed on it
    vec3 color = kAmbientIntensity * kAmbientColor + diffuse + specular;
    fragColor = vec4(mix(kBackground, color, hit), 1.0);
}
