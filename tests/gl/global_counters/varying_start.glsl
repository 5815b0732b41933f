// The entry point sets a global to a varying value, then functions advance it by constants.
float gSeed;
float advance() { gSeed += 0.1; return gSeed; }
float advanceTwice() { gSeed -= 0.047; return advance() + advance(); }
void mainImage(out vec4 o, in vec2 f) {
    gSeed = fract(f.x * 0.1371 + f.y * 0.0917) * 40.0;
    float a = advance();
    float b = advanceTwice();
    o = vec4(a, b, gSeed, fract(sin(gSeed) * 43758.5453));
}
