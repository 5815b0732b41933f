const float pi = 3.14159265;
float atan2(float y, float x) {  // gargantua's: returns from inside branches, after atan()
    if (x > 0.0) { return atan(y / x); }
    else if (x == 0.0) {
        if (y > 0.0) { return pi / 2.0; } else if (y < 0.0) { return -(pi / 2.0); } else { return 0.0; }
    } else {
        if (y >= 0.0) { return atan(y / x) + pi; } else { return atan(y / x) - pi; }
    }
}
void g(inout float acc, float t) {
    if (t < 0.3) {
        return;
    }
    float v = atan2(t - 0.6, 0.45 - t);
    acc += dFdx(v) + dFdy(v);
}
void mainImage(out vec4 c, in vec2 p) {
    float acc = 0.0;
    for (int i = 0; i < STEPS; i++) {
        g(acc, fract(p.x * 0.0173 + p.y * 0.0071 + float(i) * 0.37));
    }
    c = vec4(acc, 0.0, 0.0, 1.0);
}
