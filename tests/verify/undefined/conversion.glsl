// conversions of constants out of range
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    uint u = uint(-3.0) + uint(fragCoord.x);  // undefined: conversion-out-of-range
    int i = int(3.0e10) + int(fragCoord.y);  // undefined: conversion-out-of-range
    fragColor = vec4(float(u & 255u) / 255.0, float(i & 255) / 255.0, 0.5, 1.0);
}
