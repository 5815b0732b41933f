// Hard case: smoothstep with equal (and reversed) edges: undefined for edge0 >= edge1.
// The formula t = clamp((x - e0) / (e1 - e0), 0, 1) gives 0 left of the edge, 1 right of it and
// clamp(NaN) = 0 on it. llvmpipe (Mesa 22.3.6) returns garbage for equal run-time edges: values
// that change from run to run (uninitialised memory), so only our behaviour can be pinned.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float e = floor(iResolution.x * 0.5) + 0.5;   // a pixel centre: x == e on the middle column
    float equal = smoothstep(e, e, fragCoord.x);
    float reversed = smoothstep(e + 20.0, e - 20.0, fragCoord.x);
    fragColor = vec4(equal, reversed, 0.5, 1.0);
}
