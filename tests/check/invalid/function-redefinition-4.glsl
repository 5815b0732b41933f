// expect: cannot also name a function
float g;
float g() { return 1.0; } // ERROR

void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    fragColor = vec4(0.0);
}
