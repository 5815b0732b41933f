// Image.glsl (Shadertoy tab: Image) - Lab 4, part 4: Phong highlight exponents
// Purpose: compare highlight exponents: the scene drawn four times, alpha = 4 top left,
//          16 top right, 64 bottom left, 256 bottom right; higher powers focus the highlight.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Phong reflection after Bui Tuong Phong, Illumination for Computer Generated Pictures, CACM 18(6), 1975

// Solid grey behind the spheres, as in the assignment's figures.
const vec3 kBackground = vec3(0.5);

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // each quadrant is a small screen of half the resolution showing the whole scene
    vec2 halfRes = iResolution.xy * 0.5;
    // cell = (1 in the right column, 1 in the top row); it shifts the pixel into its quadrant
    vec2 cell = step(halfRes, fragCoord);
    sRay ray = calcRay(calcViewport(fragCoord - cell * halfRes, halfRes));
    // quadrant index q: 0 top left, 1 top right, 2 bottom left, 3 bottom right
    float q = cell.x + 2.0 - (cell.y + cell.y);
    // alpha = 4^(q + 1) = 2^(2q + 2): 4, 16, 64, 256, exact because exp2 of an integer is
    float alpha = exp2(q + q + 2.0);
    // nearest surface point and its unit normal; hit is 1 on a sphere, 0 elsewhere
    vec3 position;
    vec3 normal;
    float hit = traceScene(ray, position, normal);
    // the scene's point light: above and to the right of the viewer, in front of the spheres
    sPointLight light = sPointLight(vec3(1.3, 0.75, -2.5), vec3(1.0, 0.9, 0.75), 5.0);
    // V points from the surface back to the eye, which is exactly -direction of the unit
    // ray that found the surface: no subtraction and no normalize needed
    vec3 viewDir = -ray.direction;
    // I_S = k_S^alpha: the same coefficient, focused more strongly in each quadrant
    float specular = specularIntensity(normal, lightDirection(light, position), viewDir, alpha);
    // branchless background selection with the hit mask
    fragColor = vec4(mix(kBackground, vec3(specular), hit), 1.0);
}
