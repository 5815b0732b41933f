// The sky box of benchmarks/scenes/skybox (sky/, a copy) around a glossy sphere: the reflection is read with
// textureGrad, the mirrored direction's own derivatives widened by a roughness that grows toward
// the sphere's top, so the reflected sky blurs through the mipmap levels; the sky itself is read
// with its direction's derivatives given explicitly (what texture() computes itself).
// The derivatives are taken outside any branch: in a branch that only some pixels of a quad
// take they would be undefined.

// where the ray from `origin` along `dir` meets the unit sphere, or -1
float hitSphere(vec3 origin, vec3 dir)
{
    float b = dot(origin, dir);
    float c = dot(origin, origin) - 1.0;
    float disc = b * b - c;
    return disc < 0.0 ? -1.0 : -b - sqrt(disc);
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    float angle = 0.3 * iTime;
    vec3 eye = vec3(3.0 * sin(angle), 0.6, 3.0 * cos(angle));
    vec3 forward = normalize(-eye);
    vec3 right = normalize(cross(forward, vec3(0.0, 1.0, 0.0)));
    vec3 up = cross(right, forward);
    vec3 dir = normalize(forward * 1.8 + right * uv.x + up * uv.y);

    float t = hitSphere(eye, dir);
    vec3 normal = normalize(eye + max(t, 0.0) * dir);
    vec3 mirrored = reflect(dir, normal);
    float rough = 1.0 + 24.0 * smoothstep(-0.6, 0.9, normal.y);
    vec3 sky = textureGrad(iChannel0, dir, dFdx(dir), dFdy(dir)).rgb;
    vec3 glossy = textureGrad(iChannel0, mirrored, dFdx(mirrored) * rough,
                              dFdy(mirrored) * rough).rgb;
    float rim = 1.0 - 0.6 * pow(1.0 - max(dot(-dir, normal), 0.0), 3.0);
    fragColor = vec4(t > 0.0 ? glossy * rim : sky, 1.0);
}
