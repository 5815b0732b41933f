// Corpus: every operator with its precedence and associativity, and every literal form.

const int OCT = 017;
const int HEX = 0x1F;
const uint BIG = 4000000000u;
const uint HEXU = 0xFFu;
const float A = 1.;
const float B = .5;
const float C = 1e3;
const float D = 2.5E-3;
const float E = 3.0f;
const float F = 1.5e+2F;

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    ivec2 p = ivec2(fragCoord);
    int i = p.x + p.y * 3 - 7 / 2 % 5;
    int j = -i;
    j = +j;
    int k = ~j;
    k = (i << 2) >> 1;
    k = i & 0xF | j ^ 3;
    uint u = uint(p.x) * 2654435761u;
    u ^= u >> 13u;
    u = u << 3;
    i += 1; i -= 2; i *= 3; i /= 2; i %= 7;
    i <<= 1; i >>= 1; i &= 255; i |= 1; i ^= 2;
    int pre = ++i;
    int post = i++;
    --i;
    i--;
    bool a = p.x > 10 && p.y < 20 || !(p.x == p.y) ^^ p.x != 3;
    bool b = p.x <= 5 || p.y >= 7;
    float x = A + B * C - D / E;
    x = -x;
    float y = (x, A);
    float z = a ? (b ? 1.0 : 0.5) : 0.25;
    z = a ? 1.0 : b ? 0.5 : 0.0;
    float w = x = y = 0.5;
    vec3 col = vec3(float(i & 7) / 7.0, float(u % 256u) / 255.0, z * w);
    col.x *= F / 150.0;
    col = col * 0.5 + float(OCT + HEX + int(HEXU % 2u) + int(BIG % 3u)) / 1000.0;
    fragColor = vec4(col, 1.0);
}
