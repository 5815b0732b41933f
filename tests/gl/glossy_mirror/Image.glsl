// A sphere in the sky box of benchmarks/scenes/skybox (sky/, a copy), mirror-like on one side
// and glossy on the other, the glossy side turning with time. Every lookup is a textureGrad: the
// sky with its direction's own derivatives (what texture() would compute), the reflection with
// the reflected direction's derivatives widened by a roughness from 1 up to 25, so that it blurs
// through the mipmap levels. The derivatives are taken outside any branch: in a branch only
// some pixels of a quad take they would be undefined.

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    vec3 eye = vec3(0.0, 0.5, 3.2);
    vec3 dir = normalize(vec3(uv.x, uv.y - 0.3, -2.0));

    // the unit sphere at the origin: the distance along dir, or -1 where the ray misses it
    float b = dot(eye, dir);
    float disc = b * b - (dot(eye, eye) - 1.0);
    float t = disc < 0.0 ? -1.0 : -b - sqrt(disc);
    vec3 normal = normalize(eye + max(t, 0.0) * dir);
    vec3 mirrored = reflect(dir, normal);
    vec3 glossySide = normalize(vec3(sin(0.5 * iTime), 0.6, cos(0.5 * iTime)));
    float rough = 1.0 + 24.0 * clamp(dot(normal, glossySide), 0.0, 1.0);

    vec3 sky = textureGrad(iChannel0, dir, dFdx(dir), dFdy(dir)).rgb;
    vec3 shine = textureGrad(iChannel0, mirrored, dFdx(mirrored) * rough,
                             dFdy(mirrored) * rough).rgb;
    float rim = 1.0 - 0.6 * pow(1.0 - max(dot(-dir, normal), 0.0), 3.0);
    fragColor = vec4(t > 0.0 ? shine * rim : sky, 1.0);
}
