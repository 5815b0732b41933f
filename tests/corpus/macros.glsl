// Corpus: the preprocessor — object-like and function-like macros, nested expansion,
// conditionals with defined and integer expressions, #pragma, __LINE__,
// GL_ES, __VERSION__, HW_PERFORMANCE and line continuation.
#pragma optimize(on)
#define PI 3.14159265
#define TAU (2.0 * PI)
#define SQ(x) ((x) * (x))
#define MIX3(a, b, t) mix(a, b, t)
#define EMPTY()
#define LONG_SUM(a, \
                 b) ((a) + (b))
#if defined(GL_ES) && __VERSION__ >= 300 && HW_PERFORMANCE == 1
#define QUALITY 2
#elif defined HW_PERFORMANCE
#define QUALITY 1
#else
#define QUALITY 0
#endif
#ifndef QUALITY
#error QUALITY must be set
#endif
#ifdef NOT_DEFINED
this text is skipped and need not be valid GLSL
#endif
#if (QUALITY * 3 + 1) % 2 == 1 || !defined(PI) && (1 << 2) > 3
#define BRANCH 1
#else
#define BRANCH 2
#endif
#undef EMPTY

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy;
    float a = SQ(uv.x - 0.5) + SQ(uv.y - 0.5);
    float ring = 0.5 + 0.5 * cos(TAU * a * float(QUALITY) * 4.0);
    vec3 col = MIX3(vec3(0.1, 0.2, 0.4), vec3(1.0, 0.8, 0.3), ring);
    col *= LONG_SUM(0.5, \
                    0.5);
    col.r += float(__LINE__ - __LINE__ + BRANCH) * 0.01;
    fragColor = vec4(col, 1.0);
}
