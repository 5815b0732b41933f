// Image.glsl (Shadertoy tab: Image) - Lab 4, part 3: Lambert final color
// Purpose: the final Lambert color C = I_D * C_D * C_L under a dim red-orange light:
//          solid white surfaces on the left half, normal-colored ones on the right half.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/

// Solid grey behind the spheres, as in the assignment's figures.
const vec3 kBackground = vec3(0.5);
// White diffuse color for the left half: shows the light's own color unaltered.
const vec3 kWhite = vec3(1.0);

// Shadertoy entry point: uniforms are read here only and handed down as parameters.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    // viewing-plane point kept: its x also tells which half of the screen we are in
    vec2 viewport = calcViewport(fragCoord, iResolution.xy);
    sRay ray = calcRay(viewport);
    // nearest surface point and its unit normal; hit is 1 on a sphere, 0 elsewhere
    vec3 position;
    vec3 normal;
    float hit = traceScene(ray, position, normal);
    // a dim red-orange point light above and to the right of the viewer
    sPointLight light = sPointLight(vec3(1.3, 0.75, -2.5), vec3(1.0, 0.45, 0.15), 5.0);
    // C_D: white on the left half, the normal's gradient on the right (step is 1 for x >= 0)
    vec3 diffuseColor = mix(kWhite, normal * 0.5 + 0.5, step(0.0, viewport.x));
    // unit light vector and distance from one inversesqrt
    float dist;
    vec3 lightDir = lightDirection(light, position, dist);
    // I_D = k_D * I'_L, the Lambertian diffuse intensity
    float diffuse = diffuseCoefficient(normal, lightDir) * attenuation(dist, light.intensity);
    // C = I_D * C_D * C_L: the surface keeps the share of the light's color it reflects
    vec3 color = diffuse * diffuseColor * light.color;
    fragColor = vec4(mix(kBackground, color, hit), 1.0);
}
