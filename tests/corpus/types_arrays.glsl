// Corpus: types, arrays and constructors — matrices of every shape, nested and anonymous
// structs, struct names used as types everywhere, array constructors, .length(), unsized
// arrays with initializers, prototypes, overloads, parameter qualifiers, precision.

precision highp float;
precision mediump int;

struct Material { vec3 albedo; float rough; };
struct Hit { float t; Material m; vec2 uv[2]; };
struct { float a; } anon;
struct Pair { int first, second; } pairs[2];

float weight(float x);
float weight(const in float x, in float y);
void split(in vec4 v, out vec2 lo, inout vec2 hi);
Material pick(Material a, Material b, bool first);
int zero(void);

float weight(float x) { return x * 0.5; }
float weight(const in float x, in float y) { return x * y; }
int zero(void) { return 0; }

void split(in vec4 v, out vec2 lo, inout vec2 hi)
{
    lo = v.xy;
    hi += v.zw;
}

Material pick(Material a, Material b, bool first)
{
    if (first) return a;  // WebGL does not allow '?:' on structs (glslcheck/check/webgl_rules.py)
    return b;
}

highp float sum3(lowp float a, mediump float b, highp float c) { return a + b + c; }

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy;
    mat2 m2 = mat2(1.0, 2.0, 3.0, 4.0);
    mat3 m3 = mat3(m2);
    mat4 m4 = mat4(1.0);
    mat2x3 m23 = mat2x3(vec3(1.0), vec3(0.5));
    mat3x2 m32 = transpose(m23);
    mat4x3 m43 = mat4x3(0.25);
    mat2x2 m22 = m32 * m23 * m2;
    mat3x3 m33 = m3 * 2.0;
    mat2x4 m24 = mat2x4(1.0);
    mat3x4 m34 = mat3x4(1.0);
    mat4x2 m42 = mat4x2(1.0);
    mat4x4 m44 = m4;
    vec3 v3 = m23 * vec2(uv) + (vec3(uv, 1.0) * m3) * m33;
    vec4 v4 = m4 * vec4(v3, 1.0) + m24 * vec2(1.0) + m34 * vec3(0.0) + m44[3];
    v4.xy += m42 * vec4(0.0) + m43[0].xy;
    float arr[3] = float[3](0.1, 0.2, 0.3);
    float arr2[] = float[](1.0, 2.0);
    float[2] arr3 = float[2](uv.x, uv.y);
    Material mats[2] = Material[2](Material(vec3(1.0, 0.0, 0.0), 0.5), Material(vec3(0.0, 1.0, 0.0), 0.2));
    Material[2] mats2 = mats;
    Hit h;
    h.t = 1.0;
    h.m = pick(mats[0], mats2[1], uv.x < 0.5);
    h.uv[1] = uv;
    anon.a = float(arr.length() + arr2.length());
    pairs[1].second = zero(void);
    ivec3 iv = ivec3(1, 2, 3);
    uvec2 uu = uvec2(4u, 5u);
    bvec4 bb = bvec4(true, false, uv.x > 0.5, uv.y > 0.5);
    bvec2 b2 = bvec2(bb.xy);
    bvec3 b3 = bvec3(false);
    ivec2 i2 = iv.zy;
    ivec4 i4 = ivec4(i2, iv.xx);
    uvec3 u3 = uvec3(uu, 1u);
    uvec4 u4 = uvec4(u3.zyx, 0u);
    vec2 lo;
    vec2 hi = vec2(0.1);
    split(v4 * 0.001, lo, hi);
    vec3 col = h.m.albedo * weight(0.8, arr[2] + arr3[0]) + vec3(weight(hi.x) + lo.y);
    col.rgb = col.bgr * 0.5 + col.stp * 0.5;
    col += any(bb) && !all(b3) && b2.x ? vec3(0.0) : vec3(0.1 * float(i4.w + int(u4.z)));
    col.x += sum3(h.uv[1].x, h.m.rough, anon.a * 0.01);
    fragColor = vec4(col + vec3(float(pairs[1].second)), 1.0);
}
