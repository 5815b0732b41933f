// built-ins outside their domain on constants
void mainImage(out vec4 fragColor, in vec2 fragCoord)
{
    float x = fragCoord.x / iResolution.x;
    float a = pow(-2.0, 0.5);  // undefined: domain
    float b = log(0.0) + sqrt(-4.0);  // undefined: domain domain
    fragColor = vec4(x + a, x + b, clamp(pow(0.0, 0.0), 0.0, 1.0) * x, 1.0);  // undefined: domain
}
