// expect: the Common tab is compiled by Shadertoy without iTime
// tab: Common
float wave(float x)
{
    return sin(x + iTime); // ERROR
}
