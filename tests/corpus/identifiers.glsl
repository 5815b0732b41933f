// Corpus: names that look like keywords or collide with Python and the NumPy runtime.
// GLSL allows all of them; glslcheck must parse them as names and its generated Python
// must not be confused by them.

float lambda(float print) { return print * 0.5; }
float np(float self) { return self + 0.25; }

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    vec2 uv = fragCoord / iResolution.xy;
    bool trueup = uv.x > 0.5;
    float format = uv.y;
    float inputs = 0.25;
    float do_it = 0.1;
    float def = 1.0, pass_ = 0.0, yield = 0.5, import = 0.1, from = 0.2, is = 0.3;
    float None = 0.0, True = 1.0, False = 0.0, len = 2.0, range = 3.0, self = 0.5;
    float rt = 0.75, math = 0.125, numpy = 0.0625, exec = 0.5, eval = 0.25, open = 1.0;
    float elif = trueup ? format : inputs;
    float result = lambda(elif) + np(do_it) * self + def * (pass_ + yield * import + from * is);
    result += (None + True * False) + len * range * 0.01 + rt * math + numpy * exec * eval * open;
    fragColor = vec4(vec3(result * 0.5), 1.0);
}
