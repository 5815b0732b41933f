// Globals changed by *=, ++ and -- in called functions, beside a += chain.
float gProduct = 1.0;
float gSteps;
float gSeed;
float step3(float x) {
    gProduct *= 1.5;
    gSteps++;
    ++gSteps;
    gSeed += 0.1;
    return x * gProduct + gSteps;
}
float back() { gSteps--; gSeed += 0.2; return gSeed; }
void mainImage(out vec4 o, in vec2 f) {
    gSeed = f.y * 0.173;
    float a = step3(f.x * 0.01);
    float b = step3(a);
    float c = back();
    o = vec4(b, c, gProduct * gSteps, gSeed);
}
