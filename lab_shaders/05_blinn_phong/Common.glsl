// Common.glsl (Shadertoy tab: Common) - Lab 4, part 5: Blinn-Phong beside Phong
// Purpose: the sphere scene, the point light, attenuation and a diffuse plus specular
//          term that uses either Blinn-Phong or Phong highlights; reads no uniform.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Phong reflection after Bui Tuong Phong, Illumination for Computer Generated Pictures, CACM 18(6), 1975
//   Blinn-Phong halfway vector after James F. Blinn, Models of Light Reflection for Computer Synthesized Pictures, SIGGRAPH 1977

// A primary ray: where the eye is and which way this pixel looks into the scene.
struct sRay
{
    vec3 origin;    // eye position: every primary ray starts here
    vec3 direction; // unit length, so t is measured in scene units along the ray
};

// A sphere is all the lab's scene objects need: a centre and a radius.
struct sSphere
{
    vec3 center;  // centre in scene units, also the origin of its surface normals
    float radius; // radius in scene units; dividing by it makes (p - c) unit length
};

// Distance returned for "no surface": far enough to lose every depth test.
const float kNoHit = 1.0e4;
// Eye-to-viewing-plane distance: 3 units over a 2-unit-high plane gives a ~37 degree view,
// narrow enough that spheres near the frame edge are not stretched by perspective.
const float kFocalLength = 3.0;
// How many spheres the scene holds (the loop bound must be a constant in GLSL ES).
const int kSphereCount = 4;
// The scene, in front of the eye (negative z); the small front sphere overlaps the large
// one so the nearest-hit depth test is visible in the picture.
const sSphere kSpheres[kSphereCount] = sSphere[kSphereCount](
    sSphere(vec3(0.0, 0.0, -6.0), 1.2),   // large centre sphere: main lighting subject
    sSphere(vec3(-2.4, -0.5, -7.5), 0.8), // left sphere, farther back: smaller on screen
    sSphere(vec3(2.2, 0.6, -6.75), 0.7),  // right sphere, raised: lit from below-left
    sSphere(vec3(0.75, -0.75, -4.5), 0.4)); // small sphere in front, overlaps the large one

// Map a pixel onto the viewing plane: 2 units high, centred on the view axis.
vec2 calcViewport(in vec2 fragCoord, in vec2 resolution)
{
    // dividing by the height only keeps spheres round at any aspect ratio (one division)
    return (fragCoord + fragCoord - resolution) / resolution.y;
}

// Build the primary ray of a viewport point for a pinhole camera at the origin.
sRay calcRay(in vec2 viewport)
{
    // normalising once here makes the quadratic's "a" 1 and gives the view vector for free
    return sRay(vec3(0.0), normalize(vec3(viewport, -kFocalLength)));
}

// The ray position function p(t) = origin + t * direction, evaluated once per pixel.
vec3 rayAt(in sRay ray, in float t)
{
    // one multiply-add gives the surface point the normal and lighting are built on
    return ray.origin + t * ray.direction;
}

// Nearest distance at which a unit-direction ray enters a sphere, or kNoHit on a miss.
float hitSphere(in sRay ray, in sSphere sphere)
{
    // half-b quadratic (Shirley ch. 6) with a = 1: everything stays in squared form
    vec3 oc = ray.origin - sphere.center;
    float halfB = dot(oc, ray.direction);
    float c = dot(oc, oc) - sphere.radius * sphere.radius;
    // a negative discriminant means a miss; the max keeps sqrt away from negatives
    float disc = halfB * halfB - c;
    float t = -halfB - sqrt(max(disc, 0.0));
    // branchless: keep t only when the ray really hits in front of the eye
    return mix(kNoHit, t, step(0.0, disc) * step(0.0, t));
}

// Find the closest sphere along the ray; returns 1 on a hit, 0 for background.
float traceScene(in sRay ray, out vec3 position, out vec3 normal)
{
    // start with "nothing hit" and the first sphere as a harmless placeholder
    float tBest = kNoHit;
    sSphere best = kSpheres[0];
    // the nearest surface hides the others, so keep only the smallest distance
    for (int i = 0; i < kSphereCount; ++i)
    {
        // fetch once: the sphere is read by the test and by the selection below
        sSphere sphere = kSpheres[i];
        float t = hitSphere(ray, sphere);
        float closer = step(t, tBest);
        // branchless depth test: a 0/1 mix selects without a data-dependent branch
        tBest = min(t, tBest);
        best.center = mix(best.center, sphere.center, closer);
        best.radius = mix(best.radius, sphere.radius, closer);
    }
    // the ray position is evaluated a single time and reused for normal and lighting
    position = rayAt(ray, tBest);
    // a ray that kept kNoHit saw only background
    float hit = 1.0 - step(kNoHit, tBest);
    // |p - c| is the radius on the surface, so dividing by it replaces normalize(); on the
    // background the mix substitutes a unit normal so later lighting math stays finite
    normal = mix(vec3(0.0, 0.0, 1.0), (position - best.center) / best.radius, hit);
    return hit;
}

// A point light: spherical influence from one position, fading with distance.
struct sPointLight
{
    vec3 center;     // position in scene units, the same space as the spheres
    vec3 color;      // light color C_L: tints everything this light reaches
    float intensity; // I_L: how far the light reaches before fading, in scene units
};

// Unit light vector L from the surface towards the light, plus the distance d to it.
vec3 lightDirection(in sPointLight light, in vec3 position, out float dist)
{
    // squared distance first: one inversesqrt then yields both the unit vector and d
    vec3 toLight = light.center - position;
    float distSq = dot(toLight, toLight);
    float invDist = inversesqrt(distSq);
    // d = d^2 / d: a multiply instead of a second square root
    dist = distSq * invDist;
    return toLight * invDist;
}

// Attenuated intensity I'_L = 1 / (1 + d/I + d^2/I^2), rewritten over the common
// denominator I^2 as I^2 / (I^2 + d(I + d)) so the whole falloff costs one division.
float attenuation(in float dist, in float intensity)
{
    // I^2 appears once in the numerator and once in the denominator: compute it once
    float intensitySq = intensity * intensity;
    return intensitySq / (intensitySq + dist * (intensity + dist));
}

// Diffuse and specular light one point light reflects off a surface point. The highlight
// follows Blinn-Phong when blinn = 1 (N.H, exponent 4 alpha) and Phong when blinn = 0 (V.R,
// exponent alpha), so both models share one code path and can be compared side by side.
void lightTerms(in sPointLight light, in vec3 position, in vec3 normal, in vec3 viewDir,
                in vec3 diffuseColor, in vec3 specularColor, in float alpha, in float blinn,
                out vec3 diffuse, out vec3 specular)
{
    // unit light vector and distance from one inversesqrt
    float dist;
    vec3 lightDir = lightDirection(light, position, dist);
    // N.L is computed once: Lambert's coefficient and the mirror reflection both need it
    float nDotL = dot(normal, lightDir);
    // I_D = max(0, N.L) * I'_L: Lambert's cosine law faded with distance
    float diffuseIntensity = max(nDotL, 0.0) * attenuation(dist, light.intensity);
    // Blinn-Phong: H halfway between L and V; a sum of unit vectors is not unit, so normalise
    vec3 halfway = normalize(lightDir + viewDir);
    // Phong: R = reflect(-L, N) = 2(N.L)N - L, reusing N.L instead of letting reflect() redo it
    vec3 reflected = (nDotL + nDotL) * normal - lightDir;
    // the model picks the vector pair: N.H for Blinn-Phong, V.R for Phong (0/1 mix, no branch)
    float cosSpecular = dot(mix(viewDir, normal, blinn), mix(reflected, halfway, blinn));
    // alpha' = 4 alpha keeps the Blinn-Phong highlight about as large as Phong's
    float exponent = mix(alpha, 4.0 * alpha, blinn);
    // I_S = max(0, k_S)^exponent, clamped before pow (pow of a negative base is undefined)
    float specularIntensity = pow(max(cosSpecular, 0.0), exponent);
    // both reflections are tinted by the light's color C_L
    diffuse = diffuseIntensity * diffuseColor * light.color;
    specular = specularIntensity * specularColor * light.color;
}
