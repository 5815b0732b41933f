// a local read before it is assigned where the pixel is on the left half
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec3 col;
    if (fragCoord.x > 0.5 * iResolution.x) col = vec3(0.2, 0.4, 0.6);
    fragColor = vec4(col + 0.1, 1.0);  // undefined: uninitialized-local
}
