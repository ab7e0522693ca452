#version 450
// Neutral studio backdrop: a soft vertical gradient with a gentle vignette,
// so a face reads against it without a hard edge or a colour cast.
#extension GL_GOOGLE_include_directive : require

#include "frame.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  // Vulkan clip space: y = -1 is the top of the image.
  vec2 uv = frame.backdropUv.xy + inUv * frame.backdropUv.zw;
  float t = smoothstep(0.0, 1.0, uv.y);
  vec3 color = mix(frame.backgroundTop.rgb, frame.backgroundBottom.rgb, t);
  vec2 centered = uv - vec2(0.5, 0.45);
  float vignette = 1.0 - 0.35 * smoothstep(0.25, 0.85, length(centered));
  outColor = vec4(color * vignette, 1.0);
}
