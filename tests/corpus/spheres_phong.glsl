// Corpus: a lab-style lit scene (structs, loops over lights, functions, out parameters).
// Written for glslcheck's tests; exercises the common path of real student shaders.

// A point light: where it is, its color and how far it reaches.
struct PointLight
{
    vec3 center;
    vec3 color;
    float intensity;
};

// A sphere to ray trace.
struct Sphere { vec3 center; float radius; vec3 albedo; };

const int LIGHT_COUNT = 3;
const float SHININESS = 32.0;

// Intersect a ray with a sphere; returns the hit distance or -1.
float hitSphere(in Sphere s, in vec3 ro, in vec3 rd, out vec3 normal)
{
    vec3 oc = ro - s.center;
    float b = dot(oc, rd);
    float c = dot(oc, oc) - s.radius * s.radius;
    float h = b * b - c;
    if (h < 0.0) return -1.0;
    float t = -b - sqrt(h);
    vec3 p = ro + t * rd;
    normal = (p - s.center) / s.radius;
    return t;
}

// Blinn-Phong for one light.
vec3 shade(PointLight light, vec3 p, vec3 n, vec3 v, vec3 albedo)
{
    vec3 toLight = light.center - p;
    float d2 = dot(toLight, toLight);
    float d = sqrt(d2);
    vec3 l = toLight / d;
    float att = 1.0 / (1.0 + d / light.intensity + d2 / (light.intensity * light.intensity));
    float kd = max(dot(n, l), 0.0);
    vec3 h = normalize(l + v);
    float ks = pow(max(dot(n, h), 0.0), SHININESS * 4.0);
    return (kd * albedo + ks * vec3(1.0)) * light.color * att;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 ro = vec3(0.0, 0.0, 4.0);
    vec3 rd = normalize(vec3(uv, -2.0));
    PointLight lights[LIGHT_COUNT];
    lights[0] = PointLight(vec3(2.0, 2.0, 3.0), vec3(1.0, 0.6, 0.3), 6.0);
    lights[1] = PointLight(vec3(-2.0, 1.0, 2.0), vec3(0.3, 0.5, 1.0), 5.0);
    lights[2] = PointLight(vec3(0.0, -2.0 + sin(iTime), 2.0), vec3(0.8), 4.0);
    Sphere s = Sphere(vec3(0.0), 1.0, vec3(0.9, 0.9, 0.8));
    vec3 n;
    float t = hitSphere(s, ro, rd, n);
    vec3 col = mix(vec3(0.2, 0.25, 0.3), vec3(0.05), uv.y * 0.5 + 0.5);
    if (t > 0.0)
    {
        vec3 p = ro + t * rd;
        col = vec3(0.05, 0.05, 0.1);
        for (int i = 0; i < LIGHT_COUNT; i++)
        {
            col += shade(lights[i], p, n, -rd, s.albedo);
        }
    }
    fragColor = vec4(col, 1.0);
}
