// A diffuse ray tracer whose random numbers read an out seed before writing it.

// a random number in [0, 1) from the seed, which it advances (the seed is meant to be inout)
float rand(out float seed)
{
    float r = fract(sin(seed * 12.9898 + 78.233) * 43758.5453);  // undefined: out-parameter
    seed++;
    return r;
}

// a random vector in the cube [-1, 1)^3 (the seed again meant to be inout)
vec3 randVec(out float seed)
{
    return vec3(rand(seed), rand(seed), rand(seed)) * 2.0 - 1.0;
}

// a random point inside the unit sphere: draw until one falls inside
vec3 inUnitSphere(inout float seed)
{
    vec3 p;
    while (true) {
        p = randVec(seed);
        if (dot(p, p) < 1.0) break;
    }
    return p;
}

// distance along the ray to the sphere (center c, radius r), or -1.0 on a miss
float hitSphere(in vec3 c, in float r, in vec3 o, in vec3 d)
{
    vec3 oc = o - c;
    float b = dot(oc, d);
    float h = b * b - dot(oc, oc) + r * r;
    return h < 0.0 ? -1.0 : -b - sqrt(h);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 o = vec3(0.0, 0.0, 3.0);
    vec3 d = normalize(vec3(uv, -1.5));
    float seed = fragCoord.x * 0.37 + fragCoord.y * 1.91;
    vec3 col = vec3(0.6, 0.7, 0.9) * (0.5 + 0.5 * d.y);
    float t = hitSphere(vec3(0.0), 1.0, o, d);
    if (t > 0.0) {
        vec3 p = o + t * d;
        vec3 n = p;
        vec3 bounce = normalize(n + inUnitSphere(seed));
        col = vec3(0.8, 0.4, 0.3) * (0.3 + 0.7 * max(bounce.y, 0.0));
    }
    fragColor = vec4(col, 1.0);
}
