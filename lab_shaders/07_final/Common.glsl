// Common.glsl (Shadertoy tab: Common) - Lab 4, part 7: final optimised scene
// Purpose: the optimised scene: colored spheres, one ray-sphere loop, and one light
//          loop where every formula is evaluated once; reads no uniform.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted
//   Ray-sphere intersection after Peter Shirley, Ray Tracing in One Weekend, ch. 6, https://raytracing.github.io/
//   Blinn-Phong halfway vector after James F. Blinn, Models of Light Reflection for Computer Synthesized Pictures, SIGGRAPH 1977

// A primary ray: where the eye is and which way this pixel looks into the scene.
struct sRay
{
    vec3 origin;    // eye position: every primary ray starts here
    vec3 direction; // unit length, so t is measured in scene units along the ray
};

// A sphere with its own surface color, so each object reflects light differently.
struct sSphere
{
    vec3 center;  // centre in scene units, also the origin of its surface normals
    float radius; // radius in scene units; dividing by it makes (p - c) unit length
    vec3 albedo;  // diffuse reflection color C_D: the share of light the surface keeps
};

// Distance returned for "no surface": far enough to lose every depth test.
const float kNoHit = 1.0e4;
// Eye-to-viewing-plane distance: 3 units over a 2-unit-high plane gives a ~37 degree view,
// narrow enough that spheres near the frame edge are not stretched by perspective.
const float kFocalLength = 3.0;
// How many spheres the scene holds (the loop bound must be a constant in GLSL ES).
const int kSphereCount = 4;
// The scene, in front of the eye (negative z), each sphere with its own diffuse color;
// the small front sphere overlaps the large one so the depth test is visible.
const sSphere kSpheres[kSphereCount] = sSphere[kSphereCount](
    sSphere(vec3(0.0, 0.0, -6.0), 1.2, vec3(0.9, 0.9, 0.85)),   // large off-white sphere
    sSphere(vec3(-2.4, -0.5, -7.5), 0.8, vec3(0.2, 0.6, 1.0)),  // left sphere, sky blue
    sSphere(vec3(2.2, 0.6, -6.75), 0.7, vec3(1.0, 0.75, 0.2)),  // right sphere, golden
    sSphere(vec3(0.75, -0.75, -4.5), 0.4, vec3(0.9, 0.25, 0.3))); // small front sphere, red

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
float traceScene(in sRay ray, out vec3 position, out vec3 normal, out vec3 albedo)
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
        // the winning sphere's color travels with it for the lighting stage
        best.albedo = mix(best.albedo, sphere.albedo, closer);
    }
    // the ray position is evaluated a single time and reused for normal and lighting
    position = rayAt(ray, tBest);
    // a ray that kept kNoHit saw only background; a compared bool as 0 or 1 lets the mixes
    // below become selects
    float hit = float(tBest < kNoHit);
    // |p - c| is the radius on the surface, so dividing by it replaces normalize(); on the
    // background the mix substitutes a unit normal so later lighting math stays finite
    normal = mix(vec3(0.0, 0.0, 1.0), (position - best.center) / best.radius, hit);
    albedo = best.albedo; // the nearest sphere's own colour, which the lighting shades
    return hit;
}

// A point light: spherical influence from one position, fading with distance.
struct sPointLight
{
    vec3 center;     // position in scene units, the same space as the spheres
    vec3 color;      // light color C_L: tints everything this light reaches
    float intensity; // I_L: how far the light reaches before fading, in scene units
};

// How many point lights the scene holds (the loop bound must be a constant in GLSL ES).
const int kLightCount = 4;

// The light-dependent part of the lighting formula, the sum over every light i of
// (I_Di C_D + I_Si C_S) C_Li, with Blinn-Phong highlights: one loop shared by the scene.
vec3 sumLights(in sPointLight lights[kLightCount], in vec3 position, in vec3 normal,
               in vec3 viewDir, in vec3 diffuseColor, in vec3 specularColor,
               in float alphaPrime)
{
    // per-light totals of I_Di C_Li and I_Si C_Li: C_D and C_S do not depend on the light,
    // so they multiply the two sums once after the loop instead of once per light
    vec3 diffuseSum = vec3(0.0);
    vec3 specularSum = vec3(0.0);
    // light is additive: every light contributes its own reflection
    for (int i = 0; i < kLightCount; ++i)
    {
        // fetch once: the light's centre, color and intensity are each read below
        sPointLight light = lights[i];
        vec3 toLight = light.center - position;
        // one inversesqrt of the squared distance gives both the unit L and the distance d
        float distSq = dot(toLight, toLight);
        float invDist = inversesqrt(distSq);
        vec3 lightDir = toLight * invDist;
        // I'_L = I^2 / (I^2 + d I + d^2): the course's 1 / (1 + d/I + d^2/I^2) with one division,
        // and d^2 reused from above instead of squaring d again
        float intensitySq = light.intensity * light.intensity;
        float attenuated = intensitySq / (intensitySq + distSq * invDist * light.intensity + distSq);
        // I_Di = max(0, N.L) I'_L: Lambert's cosine law faded with distance
        float diffuseIntensity = max(dot(normal, lightDir), 0.0) * attenuated;
        // Blinn-Phong: H halfway between L and V; a sum of unit vectors is not unit, so normalise
        vec3 halfway = normalize(lightDir + viewDir);
        // I_Si = max(0, N.H)^alpha', clamped before pow (pow of a negative base is undefined)
        float specularIntensity = pow(max(dot(normal, halfway), 0.0), alphaPrime);
        // each reflection is tinted by this light's color C_Li
        diffuseSum += diffuseIntensity * light.color;
        specularSum += specularIntensity * light.color;
    }
    // the surface colors are applied once, outside the loop
    return diffuseSum * diffuseColor + specularSum * specularColor;
}
