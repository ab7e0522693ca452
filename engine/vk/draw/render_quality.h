#pragma once
// Quality tiers: what a frame spends its per-pixel time on. On a GPU every
// tier is cheap; on a CPU rasteriser (lavapipe) the cost is almost all per
// pixel (the shadow map's depth fill and its filter taps, the multisampled
// colour and depth, the fragment shader's terms), so a tier trades exactly
// those. `high` is the reference look; `balanced` is the same look with 2x
// instead of 4x multisampling (edges a little harder; lavapipe offers 1x or
// 4x only, so there it is 1x, its edges softened by the edge-aware pass when
// rendered headless); `fast` has no
// multisampling, no key shadow and one highlight: flatter, but the face, eyes
// and mouth still read.
#include <cstdint>
#include <optional>
#include <string_view>

#include <vulkan/vulkan.h>

#include "engine/core/enum_names.h"

namespace eng::vk {

enum class RenderQuality : uint8_t { Fast, Balanced, High };

// The defaults are `high`. Its shadow map was 2048 texels with a 5x5 filter
// until a 1024 map with 3x3 taps (each bilinear, 2x2 PCF) over the same
// penumbra measured the same picture (0.001 % of pixels off by more than
// 16/255 on facecap and the built-in head) at a third less frame time on
// lavapipe. A single tap is NOT offered: its hard-edged warm shadow reads as
// a stain on the cheek.
struct QualitySettings {
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT;  // colour and depth samples per pixel
  uint32_t shadowMapSize = 1024;  // key light's shadow map side; 0 = no shadow pass
  // Key light shadow filter: (2r+1)^2 bilinear depth-compare taps over the
  // same penumbra (lighting.glsl specialization constant 0).
  uint32_t shadowFilterRadius = 1;
  // Highlights of the fill and rim lights (the key's always stays); without
  // them the fragment shader evaluates one specular lobe instead of three
  // (specialization constant 1).
  bool secondarySpecular = true;
  // Where the target ends up with one sample: an edge-aware anti-aliasing
  // pass (edge_antialias.h) over the image before it is read back. Headless
  // targets only; a window shows its 1x image as drawn.
  bool edgeAntialias = false;
};

QualitySettings qualitySettings(RenderQuality quality);
// "fast", "balanced", "high".
inline constexpr EnumName<RenderQuality> kRenderQualityNames[] = {
    {RenderQuality::Fast, "fast"},
    {RenderQuality::Balanced, "balanced"},
    {RenderQuality::High, "high"},
};
std::string_view renderQualityName(RenderQuality quality);
// The tier a caller that names none gets ("auto"): balanced on a CPU
// rasteriser, where high's 4x multisampling alone about doubles the frame
// (lavapipe: balanced is 1x with high's shadow and highlights; the pictures
// differ only on silhouette edges), high on a GPU, where every tier is cheap.
RenderQuality defaultQuality(VkPhysicalDeviceType device);
std::optional<RenderQuality> renderQualityFromName(std::string_view name);

}  // namespace eng::vk
