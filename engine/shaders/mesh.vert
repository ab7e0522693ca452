#version 450
// Reads one vertex of one instance as morph.comp morphed it, skins it (skinned primitives), and
// transforms it to clip space.
// Built three times (see engine/vk/CMakeLists.txt): the render variant; with
// SHADOW_PASS the key light's shadow-map variant (position only; with
// ALPHA_MASK also the texture coordinate, colour and material that
// shadow_mask.frag tests); with
// MORPH_CAPTURE the capture variant that writes the morphed and skinned object-space
// vertex to a storage buffer (rasteriser discard) so tests can compare the
// GPU result with the CPU reference.
#extension GL_GOOGLE_include_directive : require

#include "frame.glsl"
#include "morph.glsl"
#include "skin.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inTexcoord;
layout(location = 3) in vec4 inTangent;  // xyz direction, w handedness (zeros when absent)
layout(location = 4) in vec4 inColor;    // multiplies the base colour (ones when absent)

// MToon's outline width mask (linear, G), read by the outline pipelines.
layout(set = 1, binding = 14) uniform sampler2D outlineWidthTexture;

#if defined(MORPH_CAPTURE)
// Three vec4 per captured vertex: position (w = 1), normal, tangent (w = handedness).
layout(std430, set = 0, binding = 3) writeonly buffer Captured { vec4 captured[]; };
#elif defined(SHADOW_PASS) && defined(ALPHA_MASK)
layout(location = 2) out vec2 outTexcoord;
layout(location = 4) out vec4 outColor;
layout(location = 5) flat out uint outMaterial;
#elif !defined(SHADOW_PASS)
layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outWorldNormal;
layout(location = 2) out vec2 outTexcoord;
layout(location = 3) flat out uint outInstance;
layout(location = 4) out vec4 outColor;
layout(location = 5) flat out uint outMaterial;  // index into instanceMaterials[]
layout(location = 6) out vec4 outWorldTangent;  // w handedness; zeros where the primitive has no tangents
#endif

// The texture coordinate through the instance's material record's UV
// transform (VRM texture transform binds).
vec2 materialTexcoord(uint material) {
  vec4 uvTransform = instanceMaterials[material].uvTransform;
  return inTexcoord * uvTransform.xy + uvTransform.zw;
}

void main() {
  uint vertex = uint(gl_VertexIndex);
  InstanceData inst = instances[gl_InstanceIndex];
  uint instanceInDraw = uint(gl_InstanceIndex) - draw.firstInstance;
  MorphedVertex m = morphedVertex(vertex, instanceInDraw, inst, inPosition, inNormal, inTangent.xyz);
  skinVertex(vertex, inst, m);

#if defined(MORPH_CAPTURE)
  uint slot = draw.captureOffset + instanceInDraw * draw.vertexCount + vertex;
  captured[slot * 3u + 0u] = vec4(m.position, 1.0);
  captured[slot * 3u + 1u] = vec4(m.normal, 0.0);
  captured[slot * 3u + 2u] = vec4(m.tangent, inTangent.w);
  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
  gl_PointSize = 1.0;
#elif defined(SHADOW_PASS)
  gl_Position = frame.keyLightViewProj * (inst.model * vec4(m.position, 1.0));
#if defined(ALPHA_MASK)
  outMaterial = inst.materialOffset + draw.material;
  outTexcoord = materialTexcoord(outMaterial);
  outColor = inColor;
#endif
#else
  vec4 world = inst.model * vec4(m.position, 1.0);
  outWorldPosition = world.xyz;
  outWorldNormal = mat3(inst.normalMatrix) * m.normal;
  outWorldTangent = vec4(mat3(inst.model) * m.tangent, inTangent.w);
  outMaterial = inst.materialOffset + draw.material;
  // MToon outline, world width: the hull pushed out along the normal, in metres.
  // The width mask scales it point by point (zero: no line there).
  vec3 outlineNormal = vec3(0.0);
  float outlineWidth = 0.0;
  outTexcoord = materialTexcoord(outMaterial);
  if (OUTLINE_PIPELINE) {
    float n2 = dot(outWorldNormal, outWorldNormal);
    outlineNormal = n2 > 1e-24 ? outWorldNormal * inversesqrt(n2) : vec3(0.0);
    InstanceMaterial material = instanceMaterials[outMaterial];
    outlineWidth = material.toonOutline.w;
    if ((draw.flags & DRAW_FLAG_TOON_OUTLINE_WIDTH_TEXTURE) != 0u)
      outlineWidth *= textureLod(outlineWidthTexture, outTexcoord, 0.0).g;
    if (material.toonOutlineStyle.x == 1.0) world.xyz += outlineNormal * outlineWidth;
  }
  outInstance = uint(gl_InstanceIndex);
  // A fold in the skin catches shadow: up to 60% darker where a target (or a
  // mix) creases it fully; the rest of the light keeps the furrow from going
  // black on a dark skin or in the key's shadow.
  outColor = vec4(inColor.rgb * (1.0 - 0.6 * clamp(m.crease, 0.0, 1.0)), inColor.a);
  gl_Position = frame.viewProj * world;
  // Screen width: a fraction of the image height whatever the distance,
  // along the normal as the image shows it.
  if (OUTLINE_PIPELINE && instanceMaterials[outMaterial].toonOutlineStyle.x == 2.0) {
    vec2 scale = abs(vec2(frame.proj[0][0], frame.proj[1][1]));
    vec2 onImage = (frame.proj * (frame.view * vec4(outlineNormal, 0.0))).xy / max(scale, vec2(1e-6));
    float length2 = dot(onImage, onImage);
    if (length2 > 1e-12)
      gl_Position.xy += onImage * inversesqrt(length2) * vec2(scale.x / scale.y, 1.0) *
                        (2.0 * outlineWidth * gl_Position.w);
  }
#endif
}
