// A global advanced in a loop of a constant count (unrolled) and in one of a varying count.
float gSeed;
float advance() { gSeed += 0.1; return gSeed; }
void mainImage(out vec4 o, in vec2 f) {
    gSeed = fract(f.x * 0.1371 + f.y * 0.0917) * 40.0;
    float sum = 0.0;
    for (int i = 0; i < 4; i++) {
        sum += advance();
    }
    float mid = gSeed;
    for (int i = 0; i < int(f.x) % 5; i++) {
        advance();
    }
    o = vec4(sum, mid, gSeed, 1.0);
}
