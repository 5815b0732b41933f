// Benchmark scene: the Lab 4 submission shape of benchmarks/scenes/lab4_submission (viewport,
// ray, spheres and point lights as structs filled through `init...(out ...)` calls), with the
// lights array declared before the branch that only the pixels hitting a sphere take and
// filled inside it (`sPointLight lights[4]; if (nearest >= 0) { initPointLight(lights[0],
// ...); ... }`), then passed whole to the lighting function. Every light is the same in every
// pixel and nothing reads the array after the branch, so a renderer that sees uniformity keeps
// it one value per frame, not one per pixel of the branch.

struct sViewport { vec2 uv; float aspect; };
struct sRay { vec3 origin; vec3 direction; };
struct sSphere { vec3 center; float radius; vec3 albedo; };
struct sPointLight { vec3 center; vec3 color; float intensity; };

void initViewport(out sViewport vp, in vec2 fragCoord, in vec2 resolution) {
    vp.aspect = resolution.x / resolution.y;
    vp.uv = fragCoord / resolution * 2.0 - 1.0;
    vp.uv.x *= vp.aspect;
}

void initRayPersp(out sRay ray, in sViewport vp, in float focalLength) {
    ray.origin = vec3(0.0, 0.0, 4.0);
    ray.direction = normalize(vec3(vp.uv, -focalLength));
}

void initSphere(out sSphere s, in vec3 center, in float radius, in vec3 albedo) {
    s.center = center;
    s.radius = radius;
    s.albedo = albedo;
}

void initPointLight(out sPointLight light, in vec3 center, in vec3 color, in float intensity) {
    light.center = center;
    light.color = color;
    light.intensity = intensity;
}

bool intersectSphere(in sSphere s, in sRay ray, out float t) {
    vec3 oc = ray.origin - s.center;
    float b = dot(oc, ray.direction);
    float c = dot(oc, oc) - s.radius * s.radius;
    float disc = b * b - c;
    t = -1.0;
    if (disc < 0.0) {
        return false;
    }
    t = -b - sqrt(disc);
    return t > 0.0;
}

float attenuation(in float dist, in float intensity) {
    float d = dist / intensity;
    return 1.0 / (1.0 + d + d * d);
}

vec3 calcLighting(in sPointLight lights[4], in vec3 position, in vec3 normal, in vec3 viewDir,
                  in vec3 albedo) {
    const float shininess = 64.0;
    vec3 ambient = 0.05 * albedo;
    vec3 diffuse = vec3(0.0);
    vec3 specular = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        vec3 toLight = lights[i].center - position;
        float dist = length(toLight);
        vec3 L = toLight / dist;
        float lambert = dot(normal, L);
        if (lambert <= 0.0) {
            continue;
        }
        float att = attenuation(dist, lights[i].intensity);
        vec3 H = normalize(L + viewDir);
        float blinn = pow(max(dot(normal, H), 0.0), shininess * 4.0);
        diffuse += lambert * att * lights[i].color;
        specular += blinn * att * lights[i].color;
    }
    return ambient + albedo * diffuse + specular;
}

vec4 calcColor(in sViewport vp, in sRay ray) {
    sSphere spheres[4];
    initSphere(spheres[0], vec3(-1.2, 0.7, 0.0), 0.8, vec3(0.9, 0.25, 0.2));
    initSphere(spheres[1], vec3(1.2, 0.7, -0.5), 0.8, vec3(0.2, 0.8, 0.3));
    initSphere(spheres[2], vec3(-1.2, -0.9, -0.5), 0.8, vec3(0.25, 0.4, 0.9));
    initSphere(spheres[3], vec3(1.2, -0.9, 0.0), 0.8, vec3(0.9, 0.8, 0.2));
    float tNearest = 1.0e6;
    int nearest = -1;
    for (int i = 0; i < 4; ++i) {
        float t;
        if (intersectSphere(spheres[i], ray, t) && t < tNearest) {
            tNearest = t;
            nearest = i;
        }
    }
    vec3 color = mix(vec3(0.05, 0.05, 0.1), vec3(0.3, 0.4, 0.6), vp.uv.y * 0.5 + 0.5);
    sPointLight lights[4];
    if (nearest >= 0) {
        initPointLight(lights[0], vec3(3.0 * cos(iTime), 3.0, 2.0), vec3(1.0, 0.85, 0.7), 6.0);
        initPointLight(lights[1], vec3(-4.0, 2.0, 3.0), vec3(0.4, 0.6, 1.0), 5.0);
        initPointLight(lights[2], vec3(0.0, -3.0, 2.5), vec3(0.3, 1.0, 0.5), 4.0);
        initPointLight(lights[3], vec3(1.0, 4.0, -3.0), vec3(1.0), 6.0);
        sSphere s = spheres[nearest];
        vec3 position = ray.origin + ray.direction * tNearest;
        vec3 normal = (position - s.center) / s.radius;
        color = calcLighting(lights, position, normal, -ray.direction, s.albedo);
        color = pow(color, vec3(1.0 / 2.2));
    }
    return vec4(color, 1.0);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    sViewport vp;
    initViewport(vp, fragCoord, iResolution.xy);
    sRay ray;
    initRayPersp(ray, vp, 2.0);
    fragColor = calcColor(vp, ray);
}
