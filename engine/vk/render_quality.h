#pragma once
// Quality tiers: what a frame spends its per-pixel time on. On a GPU every
// tier is cheap; on a CPU rasteriser (lavapipe) the cost is almost all per
// pixel (the shadow map's depth fill and its filter taps, the multisampled
// colour and depth, the fragment shader's terms), so a tier trades exactly
// those. `high` is the reference look; `balanced` and `fast` keep a face
// readable (lit, framed, eyes and mouth shaded) at a fraction of the cost.
#include <cstdint>
#include <optional>
#include <string_view>

#include <vulkan/vulkan.h>

namespace eng::vk {

enum class RenderQuality : uint8_t { Fast, Balanced, High };

struct QualitySettings {
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT;  // colour and depth samples per pixel
  uint32_t shadowMapSize = 2048;  // key light's shadow map side; 0 = no shadow pass
  // Key light shadow filter: (2r+1)^2 bilinear depth-compare taps over the
  // same penumbra (mesh.frag specialization constant 0).
  uint32_t shadowFilterRadius = 2;
  // Highlights of the fill and rim lights (the key's always stays); without
  // them the fragment shader evaluates one specular lobe instead of three
  // (specialization constant 1).
  bool secondarySpecular = true;
};

QualitySettings qualitySettings(RenderQuality quality);
// "fast", "balanced", "high".
const char* qualityName(RenderQuality quality);
std::optional<RenderQuality> parseRenderQuality(std::string_view text);

}  // namespace eng::vk
