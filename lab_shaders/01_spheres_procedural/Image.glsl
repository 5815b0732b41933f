// Image.glsl (Shadertoy tab: Image) - Lab 4, part 1: spheres, procedural
// Purpose: draw the sphere scene procedurally in image space and show each surface
//          normal as a color on a solid grey background.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted

// Solid grey behind the spheres, as in the assignment's figure.
const vec3 kBackground = vec3(0.5);

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // image-space coordinate of this pixel on the viewing plane
    vec2 coord = calcViewport(fragCoord, iResolution.xy);
    // unit normal of the nearest sphere under the pixel; hit is 1 on a sphere
    vec3 normal;
    float hit = nearestSurface(coord, normal);
    // remap the normal from [-1, 1] to [0, 1] so every direction is a visible color
    vec3 normalColor = normal * 0.5 + 0.5;
    // branchless background selection with the hit mask
    fragColor = vec4(mix(kBackground, normalColor, hit), 1.0);
}
