// A global advanced by 0.1 in a function called twice (its constants merged across the calls).
float gSeed;
float advance() { gSeed += 0.1; return gSeed; }
void mainImage(out vec4 o, in vec2 f) {
    float a = advance();
    float b = advance();
    o = vec4(a, b, fract(sin(gSeed * f.x) * 43758.5453), 1.0);
}
