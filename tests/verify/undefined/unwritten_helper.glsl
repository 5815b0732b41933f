// a helper that writes its out parameter on one path only, and one that returns early
void shade(out vec3 c, in float x)
{
    if (x > 0.5) c = vec3(0.2, 0.4, 0.6);
}  // undefined: out-parameter-unwritten

// not undefined where it is read: the caller reads t only when hit() returns true
bool hit(in float x, out float t)
{
    if (x < 0.25) return false;  // undefined: out-parameter-unwritten
    t = x;
    return true;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float x = fragCoord.x / iResolution.x;
    vec3 col = vec3(0.9);
    shade(col, x);
    float t;
    if (hit(x, t)) col.g = t;
    fragColor = vec4(col, 1.0);
}
