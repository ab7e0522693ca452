#pragma once
// Small readers of rendered RGBA8 images for assertions.
#include <cstdint>

#include <glm/glm.hpp>

#include "engine/scene/model.h"

namespace vk_test {

glm::ivec4 pixel(const eng::Image& image, int x, int y);
// Fraction of pixels whose colour differs from the background image by more than `threshold` on any channel.
double coverageAgainst(const eng::Image& image, const eng::Image& background, int threshold = 12);

}  // namespace vk_test
