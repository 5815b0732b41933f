// Hard case: undefined operations on constants, which Mesa folds at compile time with other
// answers than its run-time code: pow(-2, 2) = 4 (run time: NaN), pow(0, 0) = 1 (run time: 0),
// -7 % 2 = -1 (run time: 1), atan(0, 0) = 0 (run time: 3*pi/4). A CPU renderer folds the same
// constants only if its transpiler folds them; which column it copies is a documented choice.
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float band = floor(4.0 * fragCoord.x / iResolution.x);  // four vertical bands
    float v;
    if (band == 0.0) v = pow(-2.0, 2.0) * 0.25;             // 1.0 folded, NaN at run time
    else if (band == 1.0) v = pow(0.0, 0.0);                // 1.0 folded, 0 at run time
    else if (band == 2.0) v = float(-7 % 2) + 1.5;          // 0.5 folded, 2.5 at run time
    else v = atan(0.0, 0.0) + 0.25;                         // 0.25 folded, 2.6 at run time
    fragColor = vec4(v, 0.5, 0.5, 1.0);
}
