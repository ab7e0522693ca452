#version 450
// The key light's shadow map for glTF alphaMode MASK primitives: depth only,
// discarding where the base colour's alpha is below the cutoff.
#extension GL_GOOGLE_include_directive : require

#include "frame.glsl"
#include "base_colour.glsl"

layout(location = 2) in vec2 inTexcoord;
layout(location = 4) in vec4 inColor;
layout(location = 5) flat in uint inMaterial;

void main() {
  if (cutOut(baseColour(inTexcoord, inMaterial, inColor).a)) discard;
}
