#include "engine/vk/draw/render_quality.h"

namespace eng::vk {

QualitySettings qualitySettings(RenderQuality quality) {
  switch (quality) {
    case RenderQuality::Fast:
      return {.samples = VK_SAMPLE_COUNT_1_BIT, .shadowMapSize = 0, .shadowFilterRadius = 0,
              .secondarySpecular = false};
    case RenderQuality::Balanced:
      return {.samples = VK_SAMPLE_COUNT_2_BIT, .shadowMapSize = 1024, .shadowFilterRadius = 1,
              .secondarySpecular = true};
    case RenderQuality::High:
      break;
  }
  return {};
}

const char* qualityName(RenderQuality quality) {
  switch (quality) {
    case RenderQuality::Fast: return "fast";
    case RenderQuality::Balanced: return "balanced";
    case RenderQuality::High: return "high";
  }
  return "high";
}

std::optional<RenderQuality> parseRenderQuality(std::string_view text) {
  for (RenderQuality q : {RenderQuality::Fast, RenderQuality::Balanced, RenderQuality::High})
    if (text == qualityName(q)) return q;
  return std::nullopt;
}

}  // namespace eng::vk
