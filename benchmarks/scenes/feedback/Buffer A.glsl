// A feedback buffer for benchmarks/bench_channels.py: advects its previous frame and adds a
// moving spot; Image shows it.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    vec2 flow = 0.002 * vec2(sin(uv.y * 12.0 + iTime), cos(uv.x * 10.0 - iTime));
    vec4 prev = texture(iChannel0, uv + flow);
    vec2 spot = 0.5 + 0.3 * vec2(cos(iTime), sin(1.3 * iTime));
    float s = smoothstep(0.05, 0.0, length((uv - spot) * iResolution.xy / iResolution.y));
    fragColor = prev * 0.98 + vec4(s, 0.5 * s, 0.2 * s, 1.0);
}
