#version 300 es
// Corpus: a plain GLSL ES 3.00 fragment shader (its own #version and main), for the
// directives and qualifiers a Shadertoy tab never shows: #extension, layout, interface blocks, default qualifiers,
// interpolation qualifiers, invariant and precision on declarations.
#extension GL_EXT_shader_texture_lod : enable
#extension all : warn
precision highp float;
precision highp int;

layout(std140) uniform;
layout(std140, shared) uniform Params
{
    vec4 tint;
    highp mat4 transform;
} params;

uniform float uScale;
// Every sampler type (declared, not sampled: texture lookups come in a later stage).
uniform sampler2D s2D;
uniform samplerCube sCube;
uniform highp sampler3D s3D;
uniform highp sampler2DShadow s2DShadow;
uniform highp samplerCubeShadow sCubeShadow;
uniform highp sampler2DArray s2DArray;
uniform highp sampler2DArrayShadow s2DArrayShadow;
uniform highp isampler2D i2D;
uniform highp isampler3D i3D;
uniform highp isamplerCube iCube;
uniform highp isampler2DArray i2DArray;
uniform highp usampler2D u2D;
uniform highp usampler3D u3D;
uniform highp usamplerCube uCube;
uniform highp usampler2DArray u2DArray;
flat in int vId;
smooth in vec2 vUv;
centroid in vec3 vNormal;
in vec4 vColor;
layout(location = 0) out vec4 outColor;
invariant outColor;

const mediump vec3 GREY = vec3(0.5);

void main()
{
    lowp float k = 0.5;
    outColor = vec4(GREY * k + params.tint.rgb * uScale, 1.0);
}
