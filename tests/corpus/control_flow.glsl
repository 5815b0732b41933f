// Corpus: every statement form — if/else chains and the dangling else, switch with
// fall-through and default, while with a declaration condition, do-while, for with comma
// expressions, break, continue, early return, discard, the empty statement.

int classify(float x)
{
    if (x < 0.25) return 0;
    else if (x < 0.5) return 1;
    else if (x < 0.75)
    {
        return 2;
    }
    return 3;
}

float stepsTo(float target)
{
    float acc = 0.0;
    int n = 0;
    while (acc < target)
    {
        acc += 0.1;
        n++;
        if (n > 100) break;
    }
    do
    {
        acc -= 0.05;
    } while (acc > target);
    while (bool again = acc < 0.0) acc += 0.01;
    for (;;) { break; }
    for (int i = 0, j = 10; i < j; i++, j--)
    {
        if (i == 2) continue;
        acc += 0.001;
    }
    return acc + float(n) * 0.001;
}

vec3 palette(int k)
{
    vec3 c = vec3(0.0);
    switch (k)
    {
    case 0:
        c.r = 1.0;
    case 1:
        c.g = 0.5;
        break;
    case 2:
    {
        c.b = 1.0;
        break;
    }
    default:
        c = vec3(0.3);
    }
    return c;
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy;
    int k = classify(uv.x);
    vec3 col = palette(k);
    // Dangling else: binds to the inner if.
    if (uv.y > 0.5)
        if (uv.x > 0.9) col = vec3(1.0); else col *= 0.8;
    ;
    col += vec3(stepsTo(uv.y) * 0.1);
    if (uv.x < 0.01 && uv.y < 0.01) discard;
    fragColor = vec4(k == 3 ? col.bgr : col, 1.0);
}
