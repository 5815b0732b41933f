// Common.glsl (Shadertoy tab: Common) - Lab 4, part 1: spheres, procedural
// Purpose: image-space sphere generation with the Pythagorean theorem: a circle test on
//          the screen, then the missing z recovered from the squares already computed.
// Contributors:
//   glslcheck team - wrote and optimised this part
// Credits:
//   Starter framework: Daniel S. Buckstein, GPR-200 Lab 4 starter, adapted

// A procedural sphere: a circle on the screen plus a depth for its centre.
struct sSphere
{
    vec3 center;  // xy on the viewing plane, z = depth of the centre (larger is nearer)
    float radius; // radius in viewport units, the same unit as the coordinates
};

// How many spheres the scene holds (the loop bound must be a constant in GLSL ES).
const int kSphereCount = 4;
// Screen-space circles standing for spheres seen head-on (orthographic projection);
// the small one is nearer than the large one it overlaps, to show the depth test.
const sSphere kSpheres[kSphereCount] = sSphere[kSphereCount](
    sSphere(vec3(0.0, 0.0, 0.0), 0.6),     // large centre sphere: main subject
    sSphere(vec3(-1.05, -0.2, -0.5), 0.35), // left sphere, pushed back in depth
    sSphere(vec3(1.0, 0.25, -0.5), 0.33),   // right sphere, raised a little
    sSphere(vec3(0.48, -0.5, 0.5), 0.28));   // small sphere in front of the large one
// Depth reported when no sphere covers the pixel: loses every nearest-surface test.
const float kFarDepth = -1.0e4;

// Map a pixel onto the viewing plane: 2 units high, centred on the screen.
vec2 calcViewport(in vec2 fragCoord, in vec2 resolution)
{
    // dividing by the height only keeps circles round at any aspect ratio (one division)
    return (fragCoord + fragCoord - resolution) / resolution.y;
}

// Nearest sphere surface under a screen point; returns 1 on a sphere, 0 for background.
float nearestSurface(in vec2 coord, out vec3 normal)
{
    // no surface yet: far depth, and a placeholder normal that the mask will discard
    float zBest = kFarDepth;
    normal = vec3(0.0, 0.0, 1.0);
    // every circle is tested; the nearest covering sphere wins
    for (int i = 0; i < kSphereCount; ++i)
    {
        // 2D Pythagoras: squared distance to the circle centre, no length() or sqrt
        sSphere sphere = kSpheres[i];
        vec2 dp = coord - sphere.center.xy;
        float dxySq = dot(dp, dp);
        // r^2 = dx^2 + dy^2 + dz^2, so dz^2 reuses the squares we already have
        float rSq = sphere.radius * sphere.radius;
        float dzSq = rSq - dxySq;
        // squared in-circle test dot(dp, dp) <= r*r; it also guarantees dz^2 >= 0 inside
        float inCircle = step(dxySq, rSq);
        // the surface faces the viewer, so z is the positive root; max() only guards outside
        float dz = sqrt(max(dzSq, 0.0));
        float zSurface = sphere.center.z + dz;
        // branchless depth test: nearer surfaces (larger z) replace what is behind them
        float closer = inCircle * step(zBest, zSurface);
        zBest = mix(zBest, zSurface, closer);
        // |(dx, dy, dz)| is the radius, so dividing by it normalises without normalize()
        normal = mix(normal, vec3(dp, dz) / sphere.radius, closer);
    }
    // anything that kept the far depth is background
    return step(kFarDepth + 1.0, zBest);
}
