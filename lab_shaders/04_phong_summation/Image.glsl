// Image.glsl (Shadertoy tab: Image) - Lab 4, part 4: Phong summation
// Purpose: show the Phong summation in four quadrants: ambient (top left), diffuse
//          (top right), specular (bottom left) and their sum, the Phong color (bottom right).
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
    // each quadrant is a small screen of half the resolution showing the whole scene
    vec2 halfRes = iResolution.xy * 0.5;
    // cell = (1 in the right column, 1 in the top row); it shifts the pixel into its quadrant
    vec2 cell = step(halfRes, fragCoord);
    sRay ray = calcRay(calcViewport(fragCoord - cell * halfRes, halfRes));
    // nearest surface point and its unit normal; hit is 1 on a sphere, 0 elsewhere
    vec3 position;
    vec3 normal;
    float hit = traceScene(ray, position, normal);
    // red-orange point light above and to the right of the viewer, in front of the spheres
    sPointLight light = sPointLight(vec3(1.3, 0.75, -2.5), vec3(1.0, 0.5, 0.2), 9.0);
    // V points from the surface back to the eye, which is exactly -direction of the unit
    // ray that found the surface: no subtraction and no normalize needed
    vec3 viewDir = -ray.direction;
    // the three components of C = I_A C_A + (I_D C_D + I_S C_S) C_L, with the normal as C_D
    vec3 diffuse;
    vec3 specular;
    phongTerms(light, position, normal, viewDir, normal * 0.5 + 0.5, kSpecularColor, kAlpha, diffuse, specular);
    // branchless quadrant weights: ambient shows top left and bottom right (cell.x != cell.y),
    // diffuse in the right column, specular in the bottom row: the bottom right gets all three
    float ambientWeight = abs(cell.x - cell.y);
    vec3 color = (ambientWeight * kAmbientIntensity) * kAmbientColor + cell.x * diffuse + (1.0 - cell.y) * specular;
    fragColor = vec4(mix(kBackground, color, hit), 1.0);
}
