#include "tests/engine/vk/image_probe.h"

#include <algorithm>
#include <cstdlib>

namespace vk_test {

glm::ivec4 pixel(const eng::Image& image, int x, int y) {
  const uint8_t* p = &image.rgba8[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
  return {p[0], p[1], p[2], p[3]};
}

double coverageAgainst(const eng::Image& image, const eng::Image& background, int threshold) {
  size_t covered = 0;
  const size_t pixels = image.rgba8.size() / 4;
  for (size_t i = 0; i < pixels; ++i) {
    int worst = 0;
    for (size_t c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(image.rgba8[i * 4 + c]) - int(background.rgba8[i * 4 + c])));
    if (worst > threshold) ++covered;
  }
  return pixels ? double(covered) / double(pixels) : 0.0;
}

}  // namespace vk_test
