#pragma once
// C++ mirrors of the GLSL interface in engine/shaders/frame.glsl and
// mesh.frag. Sizes are asserted so a change on one side cannot go unnoticed.
#include <cstdint>

#include <glm/glm.hpp>

namespace eng::vk {

// One non-zero morph weight (std430: 8 bytes).
struct ActiveWeight {
  uint32_t target = 0;  // index among the drawn mesh's targets
  float weight = 0.0f;
};
static_assert(sizeof(ActiveWeight) == 8);

struct GpuInstance {
  glm::mat4 model{1.0f};
  glm::mat4 normalMatrix{1.0f};
  uint32_t activeOffset = 0;
  uint32_t activeCount = 0;
  uint32_t jointOffset = 0;  // first joint matrix of the instance's skin (skin.glsl)
  uint32_t jointCount = 0;   // 0 = not skinned
  uint32_t materialOffset = 0;  // first of the instance's material records (InstanceMaterial)
  uint32_t weightOffset = 0;    // first weight of the drawn mesh's targets in the slot's target weights (morph.glsl)
  uint32_t reserved[2] = {};    // std430 rounds the struct to 16 bytes
};
static_assert(sizeof(GpuInstance) == 160);

// The material parameters an animation may move, per instance and per frame
// (std430, 48 bytes): VRM material colour and texture transform binds. Each
// instance draws with one record per material of its model, the model's own
// values (GpuModel::materials()) unless the instance overrides them.
struct InstanceMaterial {
  glm::vec4 baseColorFactor{1.0f};                // linear RGBA, multiplies the base colour texture
  glm::vec4 emissive{0.0f};                       // linear RGB emission added to the shaded colour, w unused
  glm::vec4 uvTransform{1.0f, 1.0f, 0.0f, 0.0f};  // texture coordinates uv * xy + zw
  // MToon (kDrawFlagToon draws only), eng::ToonShading:
  glm::vec4 toonShade{0.0f};    // linear RGB shade colour, w rim lift
  glm::vec4 toonShading{0.0f, 0.9f, 0.9f, 1.0f};  // shading shift, toony, GI equalization, rim lighting mix
  glm::vec4 toonRim{0.0f, 0.0f, 0.0f, 5.0f};      // linear RGB rim colour, w fresnel power
  glm::vec4 toonOutline{0.0f};                    // linear RGB outline colour, w width (metres or image heights)
  glm::vec4 toonOutlineStyle{0.0f, 1.0f, 0.0f, 0.0f};  // x: 1 world width, 2 screen width; y: lighting mix
  glm::vec4 toonMatcap{1.0f, 1.0f, 1.0f, 0.0f};        // linear RGB matcap factor (kDrawFlagToonMatcap), w unused
};
static_assert(sizeof(InstanceMaterial) == 144);

// std140 uniform block; every member is a mat4 or vec4.
struct FrameGlobals {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};
  glm::mat4 viewProj{1.0f};
  glm::vec4 cameraPosition{0.0f};
  glm::vec4 keyDirection{0.0f};
  glm::vec4 keyColor{0.0f};
  glm::vec4 fillDirection{0.0f};
  glm::vec4 fillColor{0.0f};
  glm::vec4 rimDirection{0.0f};
  glm::vec4 rimColor{0.0f};
  glm::vec4 skyAmbient{0.0f};
  glm::vec4 groundAmbient{0.0f};
  glm::vec4 backgroundTop{0.0f};
  glm::vec4 backgroundBottom{0.0f};
  glm::vec4 skin{0.0f};  // wrap, subsurface strength, specular strength, exposure
  glm::vec4 subsurfaceColor{0.0f};
  glm::mat4 keyLightViewProj{1.0f};
  glm::vec4 shadow{0.0f};  // unused, filter radius (uv), normal offset (world), enabled
  glm::vec4 shadowColor{0.0f};
  // The backdrop's place in the whole picture: its uv = xy + view uv * zw (a
  // window's 3D view drawn for a region of it keeps the window's gradient).
  glm::vec4 backdropUv{0.0f, 0.0f, 1.0f, 1.0f};
};
static_assert(sizeof(FrameGlobals) == 4 * 64 + 16 * 16);

struct DrawConstants {
  float roughness = 0.6f;
  float metallic = 0.0f;
  uint32_t detailLayerCount = 0;
  uint32_t flags = 0;
  uint32_t vertexCount = 0;
  uint32_t firstInstance = 0;
  uint32_t captureOffset = 0;
  uint32_t jointSets = 0;  // groups of four joint influences per vertex, 0 = not skinned
  uint32_t material = 0;   // the primitive's record among its instance's InstanceMaterial records
  uint32_t morphOffset = 0;  // first vec4 of the draw's morphed vertices (morph.glsl)
  // Float offsets of the rest position, normal and tangent arrays in the
  // model's vertex buffer (the morph pre-pass reads them as storage).
  uint32_t restPosition = 0;
  uint32_t restNormal = 0;
  uint32_t restTangent = 0;
  // Bit l set: detail layer l may show in this draw (some instance's weight
  // for its target is not zero). Filled per frame by the scene renderer, so
  // a fragment samples only the layers that can show: on a CPU rasteriser
  // every layer sampled costs every pixel of the skin, whatever its weight.
  uint32_t detailLayerMask = 0;
  float alphaCutoff = 0.5f;  // kDrawFlagAlphaMask: fragments with less base-colour alpha are discarded
  float normalScale = 1.0f;        // kDrawFlagNormalMap: scales the normal texture's x and y
  float occlusionStrength = 0.0f;  // 0: no occlusion texture (or one of strength 0)
  float toonShadingShiftScale = 1.0f;  // kDrawFlagToonShadingShiftTexture: scales the texture's red
};
static_assert(sizeof(DrawConstants) == 72);

enum DrawFlags : uint32_t {
  kDrawFlagNormalDeltas = 1u,
  kDrawFlagTangentDeltas = 2u,
  kDrawFlagDoubleSided = 4u,
  kDrawFlagCreases = 8u,  // the primitive has crease darkening (in its sparse delta entries)
  kDrawFlagMorphed = 16u, // the primitive has sparse deltas: the morph pre-pass writes its vertices
  kDrawFlagMirrored = 32u, // the instances' transform has a negative determinant: front faces wind clockwise
  kDrawFlagAlphaMask = 64u,   // glTF alphaMode MASK: cut out below alphaCutoff
  kDrawFlagAlphaBlend = 128u, // glTF alphaMode BLEND: drawn after the opaque draws, back to front, blended
  kDrawFlagUnlit = 256u,      // KHR_materials_unlit: the base colour as it is, no lights
  kDrawFlagToon = 512u,       // MToon: toon shading from InstanceMaterial's toon* values
  kDrawFlagToonShadeTexture = 1024u,  // MToon: the shade colour is multiplied by the base colour's texture
  kDrawFlagToonOutline = 2048u,       // MToon: drawn again as an outline (ScenePipelines::outline)
  kDrawFlagNormalMap = 4096u,         // glTF normalTexture: the shading normal bent by it
  kDrawFlagEmissiveTexture = 8192u,   // glTF emissiveTexture: the emission masked by it
  kDrawFlagToonMatcap = 16384u,       // MToon matcap texture (set 1 binding 11), added with the rim
  kDrawFlagToonShadingShiftTexture = 32768u,  // MToon shadingShiftTexture (set 1 binding 12)
  kDrawFlagToonRimMultiply = 65536u,          // MToon rimMultiplyTexture (set 1 binding 13)
  kDrawFlagToonOutlineWidthTexture = 131072u, // MToon outlineWidthMultiplyTexture (set 1 binding 14)
};

struct GpuDetailLayer {
  uint32_t target = 0;
  float strength = 1.0f;
  uint32_t modulate = 0;  // DetailBlend::Modulate
};
static_assert(sizeof(GpuDetailLayer) == 12);

// One captured vertex (three vec4 in the capture buffer).
struct GpuCapturedVertex {
  glm::vec4 position;
  glm::vec4 normal;
  glm::vec4 tangent;
};
static_assert(sizeof(GpuCapturedVertex) == 48);

}  // namespace eng::vk
