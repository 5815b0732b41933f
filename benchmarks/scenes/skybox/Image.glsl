// A mirror sphere in a sky box: the sky is a cube map on iChannel0 (channels.json), seen
// around the sphere and reflected in it, with a rim darkened by a Fresnel-like term.

// the ray from the camera through this pixel, and where it meets the unit sphere (or -1)
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

    vec3 color = texture(iChannel0, dir).rgb;
    float t = hitSphere(eye, dir);
    if (t > 0.0)
    {
        vec3 normal = normalize(eye + t * dir);
        vec3 mirrored = reflect(dir, normal);
        float rim = 1.0 - 0.6 * pow(1.0 - max(dot(-dir, normal), 0.0), 3.0);
        color = texture(iChannel0, mirrored).rgb * rim;
    }
    fragColor = vec4(color, 1.0);
}
