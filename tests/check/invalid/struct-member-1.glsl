// expect: has no member 'radius'
struct Sphere { vec3 center; float r; };
float f(Sphere s)
{
    return s.radius; // ERROR
}

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
