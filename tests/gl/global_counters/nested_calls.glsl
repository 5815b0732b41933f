// A global written by a function that another function calls; initialized, and uninitialized.
float gCount = 2.5;
float gScale;
void bump() { gCount += 1.0; gScale -= 0.25; }
float bumpAndRead(float x) { bump(); bump(); return x * gCount + gScale; }
void mainImage(out vec4 o, in vec2 f) {
    float a = bumpAndRead(f.x * 0.01);
    float b = bumpAndRead(f.y * 0.01);
    o = vec4(a, b, gCount, gScale);
}
