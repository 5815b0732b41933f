// A global counter advanced in a function mainImage calls once.
float gCount;
vec3 shadeCounting(vec3 n) { gCount += 1.0; return n * gCount; }
void mainImage(out vec4 o, in vec2 f) {
    vec3 n = vec3(f * 0.01, 1.0);
    vec3 color = shadeCounting(n);
    o = vec4(color, gCount);
}
