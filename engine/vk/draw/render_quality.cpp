#include "engine/vk/draw/render_quality.h"

namespace eng::vk {

QualitySettings qualitySettings(RenderQuality quality) {
  switch (quality) {
    case RenderQuality::Fast:
      return {.samples = VK_SAMPLE_COUNT_1_BIT, .shadowMapSize = 0, .shadowFilterRadius = 0,
              .secondarySpecular = false};
    case RenderQuality::Balanced:
      return {.samples = VK_SAMPLE_COUNT_2_BIT, .shadowMapSize = 1024, .shadowFilterRadius = 1,
              .secondarySpecular = true, .edgeAntialias = true};
    case RenderQuality::High:
      break;
  }
  return {};
}

std::string_view renderQualityName(RenderQuality quality) { return nameOf(kRenderQualityNames, quality); }

RenderQuality defaultQuality(VkPhysicalDeviceType device) {
  return device == VK_PHYSICAL_DEVICE_TYPE_CPU ? RenderQuality::Balanced : RenderQuality::High;
}

std::optional<RenderQuality> renderQualityFromName(std::string_view name) { return valueNamed(kRenderQualityNames, name); }

}  // namespace eng::vk
