// A textured scene for benchmarks/bench_channels.py: a rotating, zooming plane that samples
// iChannel0 (mipmap: every LOD from 0 up) and iChannel1 (linear, repeat); the texture is made
// by the benchmark (tex.png, noise) so no image file is committed.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 p = (2.0 * fragCoord - iResolution.xy) / iResolution.y;
    float a = 0.3 * iTime;
    mat2 r = mat2(cos(a), -sin(a), sin(a), cos(a));
    vec2 uv = r * p / (0.2 + abs(p.y)) + vec2(0.0, iTime);
    vec4 c = texture(iChannel0, uv * 0.25);
    vec4 d = texture(iChannel1, uv * 2.0 + c.xy);
    fragColor = vec4(mix(c.rgb, d.rgb, 0.3) * abs(p.y), 1.0);
}
